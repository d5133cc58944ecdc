// The interactive editor's logic without a window: session log + lock + crash recovery (editor/session/session.h),
// Save/Open round trip, the Sketch placement tool's "parameter change = one undoable re-run", picking, and the
// navigation maths (editor/session/navigation.h). The window itself is checked by the xvfb screenshot test.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/sketch_tool.h"
#include "session_test_util.h"
#include "stroke_gesture.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using AppSession = test::StateDirTest;
using test::kBox, test::kTeapot, test::line_count;

}  // namespace

TEST_F(AppSession, StateDirHonoursOverride) { EXPECT_EQ(editor::state_dir(), dir_); }

TEST_F(AppSession, LogIsWrittenAtOnceAndLockRemovedOnCleanExit) {
  {
    editor::EditorSession s(messages_);
    EXPECT_FALSE(s.start(true));
    EXPECT_TRUE(fs::exists(dir_ / "session.lock"));
    ASSERT_TRUE(s.execute(kTeapot));
    EXPECT_EQ(line_count(dir_ / "session.jsonl"), 1u);  // flushed before the next command
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(line_count(dir_ / "session.jsonl"), 2u);  // + edit.undo
    s.finish();
  }
  EXPECT_FALSE(fs::exists(dir_ / "session.lock"));
  editor::EditorSession next(messages_);
  EXPECT_FALSE(next.start(true)) << "a clean exit must not offer recovery";
}

TEST_F(AppSession, UnfinishedSessionIsOfferedAndRecovered) {
  {
    editor::EditorSession crashed(messages_);
    crashed.start(true);
    ASSERT_TRUE(crashed.execute(kTeapot));
    ASSERT_TRUE(crashed.execute(kBox));
    ASSERT_TRUE(crashed.undo());
    // no finish(): the lock stays, as after a crash or a kill
  }
  std::ofstream(dir_ / "session.jsonl", std::ios::app) << "{\"cmd\":\"scene.prim";  // torn last line
  editor::EditorSession s(messages_);
  const auto offer = s.start(true);
  ASSERT_TRUE(offer);
  EXPECT_EQ(offer->commands, 3u);  // teapot, crate, edit.undo; the torn line is dropped
  ASSERT_TRUE(s.recover(*offer));
  EXPECT_EQ(s.scene().objects().size(), 1u);
  EXPECT_EQ(s.history().applied(), 1u);
  EXPECT_TRUE(s.history().can_redo()) << "recovered history keeps the undone command";
  s.finish();
}

TEST_F(AppSession, UnansweredRecoveryIsAskedAgain) {
  test::crash_with({kTeapot});
  {
    editor::EditorSession asked(messages_);
    ASSERT_TRUE(asked.start(true));
  }  // dies before the user answers
  editor::EditorSession again(messages_);
  const auto offer = again.start(true);
  ASSERT_TRUE(offer);
  EXPECT_EQ(offer->commands, 1u);
  again.discard(*offer);
  again.finish();
  editor::EditorSession after(messages_);
  EXPECT_FALSE(after.start(true)) << "answered: not asked again";
  after.finish();
}

TEST_F(AppSession, ErrorsGoToTheLogAndLeaveTheScene) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot}));
  const std::size_t errors = messages_.error_count();
  EXPECT_FALSE(s.execute({{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "teapot"}}));  // name taken
  EXPECT_FALSE(s.execute({{"cmd", "no.such.command"}}));
  EXPECT_EQ(messages_.error_count(), errors + 2);
  EXPECT_EQ(s.scene().objects().size(), 1u);
  EXPECT_EQ(s.history().size(), 1u);
  s.finish();
}

TEST_F(AppSession, SaveThenOpenReplaysTheSameSceneAndView) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot, kBox}));
  core::Camera view;
  view.eye = {1, 2, 5};
  view.viewport = {640, 480};
  const fs::path saved = dir_ / "saved.jsonl";
  ASSERT_TRUE(s.save(saved, view));
  EXPECT_FALSE(s.modified());
  EXPECT_EQ(line_count(saved), 3u);  // two commands + camera.set

  editor::EditorSession t(messages_);
  ASSERT_TRUE(t.open(saved));
  EXPECT_EQ(t.scene().objects().size(), 2u);
  EXPECT_EQ(t.history().applied(), 3u);  // one undoable step per line
  EXPECT_TRUE(t.scene().camera_set);
  EXPECT_EQ(t.scene().camera.eye, view.eye);
  EXPECT_FALSE(t.modified());
  s.finish();
}

// Open is a transaction: a log whose second line fails leaves the open document exactly as it was — scene, history,
// title, modified flag and session log — instead of a half-opened scene that a later Save would write over the file.
TEST_F(AppSession, OpenOfALogThatFailsHalfwayKeepsTheCurrentDocument) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot}));
  core::Camera view;
  const fs::path good = dir_ / "good.jsonl";
  ASSERT_TRUE(s.save(good, view));
  ASSERT_TRUE(s.execute(kBox));  // an unsaved change
  const fs::path bad = dir_ / "bad.jsonl";
  {
    std::ofstream out(bad);
    out << R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"
        << "\n";
    out << R"({"cmd":"scene.load","path":"does_not_exist.obj","name":"m"})"
        << "\n";
  }
  const std::size_t log_lines = line_count(dir_ / "session.jsonl");
  const std::size_t applied = s.history().applied();
  const auto teapot_mesh = s.scene().find("teapot")->world_mesh;
  EXPECT_FALSE(s.open(bad));
  EXPECT_EQ(s.scene().objects().size(), 2u);
  EXPECT_EQ(s.scene().find("ball"), nullptr) << "line 1 of the failed log must not be applied";
  EXPECT_EQ(s.scene().find("teapot")->world_mesh, teapot_mesh);
  EXPECT_EQ(s.history().applied(), applied);
  EXPECT_EQ(s.document(), good);
  EXPECT_TRUE(s.modified());
  EXPECT_EQ(line_count(dir_ / "session.jsonl"), log_lines) << "the session log must not be restarted";
  ASSERT_FALSE(messages_.messages().empty());
  EXPECT_NE(messages_.messages().back().text.find("bad.jsonl:2:"), std::string::npos)
      << messages_.messages().back().text;
  EXPECT_NE(messages_.messages().back().text.find("current scene is kept"), std::string::npos);

  // A good Open then replaces the document, and the session log replays to it (crash recovery stays exact).
  ASSERT_TRUE(s.undo());  // a redo tail: it must survive as edit.undo lines
  const fs::path two = dir_ / "two.jsonl";
  ASSERT_TRUE(s.save(two, view));
  editor::EditorSession t(messages_);
  ASSERT_TRUE(t.open(good));
  EXPECT_EQ(t.scene().objects().size(), 1u);
  EXPECT_FALSE(t.modified());
  s.finish();
}

TEST_F(AppSession, SketchParameterChangeReRunsAsOneUndoableStep) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot, kBox}));
  core::Camera view = test::framed_view(s.scene(), "teapot");
  test::SketchToolRig rig(s, view);
  editor::SketchTool& tool = rig.tool;
  editor::ToolContext& ctx = rig.ctx;

  // A stroke across the middle of the view (over the teapot's body).
  rig.press_stroke();
  rig.drag_stroke();
  rig.release_stroke();
  ASSERT_EQ(s.history().applied(), 3u) << (messages_.messages().empty() ? "" : messages_.messages().back().text);
  EXPECT_EQ(s.history().at(2).id(), "place.sketch");
  EXPECT_TRUE(s.history().at(2).to_json().contains("camera")) << "the line must carry its view";
  ASSERT_TRUE(tool.can_rerun(ctx));
  const auto placed = s.scene().find("crate")->world_mesh;

  core::PlaceSketchParams p = tool.params();
  p.height *= 2;
  tool.set_params(p, ctx);
  EXPECT_EQ(s.history().applied(), 3u) << "a parameter change replaces the placement, it does not stack";
  EXPECT_EQ(s.history().size(), 3u);
  EXPECT_EQ(s.history().at(2).to_json()["height"].get<double>(), p.height);
  EXPECT_NE(s.scene().find("crate")->world_mesh, placed);

  core::PlaceSketchParams bad = p;
  bad.width = -1;  // rejected by the command: the previous placement must come back
  const auto before_bad = s.scene().find("crate")->world_mesh->positions;
  tool.set_params(bad, ctx);
  EXPECT_EQ(s.history().applied(), 3u);
  EXPECT_EQ(s.scene().find("crate")->world_mesh->positions, before_bad);

  ASSERT_TRUE(s.undo());  // one undo goes back to before the placement
  EXPECT_EQ(s.scene().find("crate")->ffd, nullptr);
  s.finish();
}

TEST(AppPick, PicksTheObjectUnderTheCursor) {
  ui::MessageLog messages;
  editor::EditorSession s(messages);
  ASSERT_TRUE(s.execute(kTeapot));
  editor::Navigator nav;
  nav.frame(s.scene().bounds(), {400, 300});
  const core::Camera c = nav.camera({400, 300});
  EXPECT_EQ(editor::pick_object(s.scene(), c, {200, 150}).value_or(""), "teapot");
  EXPECT_FALSE(editor::pick_object(s.scene(), c, {2, 2}));
  ASSERT_TRUE(s.execute({{"cmd", "object.visibility"}, {"object", "teapot"}, {"viewport", false}}));
  EXPECT_FALSE(editor::pick_object(s.scene(), c, {200, 150})) << "hidden objects are not picked";
}

TEST(AppNavigation, OrbitPanZoomFrame) {
  editor::Navigator nav;
  core::Camera start;
  start.eye = {0, 0, 5};
  start.target = {0, 0, 0};
  nav.set_from_camera(start);
  core::Camera c = nav.camera({800, 600});
  EXPECT_NEAR(glm::length(c.eye - start.eye), 0.0, 1e-9);

  nav.orbit({100, 0});  // turntable: distance and height kept
  c = nav.camera({800, 600});
  EXPECT_NEAR(glm::length(c.eye - c.target), 5.0, 1e-9);
  EXPECT_NEAR(c.eye.y, 0.0, 1e-9);

  const glm::dvec3 pivot = nav.pivot();
  nav.pan({40, 0}, {800, 600});
  EXPECT_GT(glm::length(nav.pivot() - pivot), 0.0);

  const double d = nav.distance();
  nav.zoom(1, {400, 300}, {800, 600});  // at the centre: pivot stays, distance shrinks
  EXPECT_LT(nav.distance(), d);

  core::Aabb box;
  box.extend({-1, -1, -1});
  box.extend({1, 1, 1});
  nav.frame(box, {800, 600});
  c = nav.camera({800, 600});
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-1.0, 1.0}) {
        const glm::dvec3 px = c.project({x, y, z});
        EXPECT_GT(px.z, 0);
        EXPECT_GE(px.x, 0);
        EXPECT_LE(px.x, 800);
        EXPECT_GE(px.y, 0);
        EXPECT_LE(px.y, 600);
      }
}
