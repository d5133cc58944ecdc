// Fill built on a worker thread (editor/session/background_command.h): a cancelled fill leaves the scene, the history
// and the session log untouched and says "Fill cancelled"; other changes are refused while it builds; a finished one is
// one history entry whose log line and resulting layer are bit for bit those of the same line executed synchronously
// (what replay does). No timing is asserted: a cancel that arrives after the build finished drops it all the same.
// Undo, redo and History jumps walked on the worker end where the synchronous ones do.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>

#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_remove.h"
#include "editor/commands/command_registry.h"
#include "editor/session/background_command.h"
#include "session_test_util.h"
#include "tests/test_paths.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

// ddm.fill of the teapot's body with thorns 0.08 world units across (~450 tiles, ~280 K tile vertices: a few
// progress steps, short enough for a test).
nlohmann::json fill_line() {
  core::DdmFillParams p;
  p.object = "teapot";
  p.layer = "tiles";
  p.spec.tiles = {"thorn"};
  p.spec.tile_size = 0.08;
  p.spec.height = 0.1;
  p.spec.base = core::DdmBaseKind::teapot_body;
  return core::DdmFillCommand::schema().to_json(p);
}

std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

class BackgroundCommandTest : public test::StateDirTest {};

TEST_F(BackgroundCommandTest, CancelledFillChangesNothingAndIsNotLogged) {
  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.execute(test::kTeapot));
  const std::size_t lines = test::line_count(dir_ / "session.jsonl");
  const core::SceneObject before = *s.scene().find("teapot");
  {
    editor::BackgroundCommand bg(s);
    ASSERT_TRUE(bg.start(fill_line(), "Filling teapot with thorn", "Fill"));
    EXPECT_TRUE(bg.running());
    // The document is frozen while it builds: commands and undo are refused, not queued.
    EXPECT_FALSE(s.execute(test::kBox));
    EXPECT_FALSE(s.undo());
    EXPECT_TRUE(logged("refused: Filling teapot with thorn"));
    EXPECT_FALSE(bg.start(fill_line(), "Filling again", "Fill")) << "one build at a time";
    bg.cancel();
    EXPECT_TRUE(bg.cancelling());
    bg.wait();
    EXPECT_FALSE(bg.finish());
    EXPECT_FALSE(bg.running());
  }
  EXPECT_TRUE(logged("Fill cancelled"));
  EXPECT_TRUE(s.busy().empty());
  EXPECT_EQ(s.history().size(), 1u);
  EXPECT_EQ(test::line_count(dir_ / "session.jsonl"), lines) << "nothing logged";
  const core::SceneObject& after = *s.scene().find("teapot");
  EXPECT_TRUE(after.ddm_layers.empty());
  EXPECT_EQ(after.world_mesh, before.world_mesh);
  EXPECT_EQ(s.scene().objects().size(), 1u) << "the refused crate was not queued";
  EXPECT_TRUE(s.execute(test::kBox)) << "changes are accepted again";
}

TEST_F(BackgroundCommandTest, BackgroundFillIsBitForBitTheSynchronousOne) {
  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.execute(test::kTeapot));
  editor::BackgroundCommand bg(s);
  ASSERT_TRUE(bg.start(fill_line(), "Filling teapot with thorn", "Fill"));
  bg.wait();
  EXPECT_GE(bg.progress(), 0.9) << "the build reported its progress";
  ASSERT_TRUE(bg.finish());
  EXPECT_FALSE(bg.running());
  ASSERT_EQ(s.history().size(), 2u);
  EXPECT_EQ(s.history().at(1).id(), "ddm.fill");

  // The same lines run synchronously, as replay runs them.
  core::Scene sync;
  editor::History history(sync);
  const core::CommandContext ctx{fs::current_path(), {}};
  history.execute(editor::CommandRegistry::builtin().parse(test::kTeapot, ctx));
  history.execute(editor::CommandRegistry::builtin().parse(fill_line(), ctx));
  EXPECT_EQ(s.history().at(1).to_json().dump(), history.at(1).to_json().dump());
  EXPECT_EQ(nlohmann::json::parse(last_line(dir_ / "session.jsonl")), history.at(1).to_json())
      << "one log line, the same";

  const core::DdmLayer& a = *s.scene().find("teapot")->ddm_layers.at(0);
  const core::DdmLayer& b = *sync.find("teapot")->ddm_layers.at(0);
  EXPECT_GT(a.instances.size(), 300u);
  EXPECT_EQ(a.instances, b.instances);
  EXPECT_TRUE(same_bits(a.maps->samples, b.maps->samples));
  EXPECT_TRUE(same_bits(a.mesh->positions, b.mesh->positions));
  EXPECT_TRUE(same_bits(a.mesh->normals, b.mesh->normals));
  EXPECT_TRUE(same_bits(a.mesh->triangles, b.mesh->triangles));

  // Undo and redo move it as one step.
  const auto layer = s.scene().find("teapot")->ddm_layers.at(0);
  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.scene().find("teapot")->ddm_layers.empty());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.scene().find("teapot")->ddm_layers.at(0), layer);
}

TEST_F(BackgroundCommandTest, FailingAndNonPreparableLinesReportAsExecuteDoes) {
  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.execute(test::kTeapot));
  editor::BackgroundCommand bg(s);
  nlohmann::json bad = fill_line();
  bad["object"] = "nothing";
  ASSERT_TRUE(bg.start(bad, "Filling nothing", "Fill"));  // fails on its worker
  bg.wait();
  EXPECT_FALSE(bg.finish());
  EXPECT_TRUE(logged("ddm.fill: field 'object'"));
  EXPECT_EQ(s.history().size(), 1u);
  EXPECT_TRUE(bg.start(test::kBox, "Adding a box", "Add")) << "not preparable: runs at once";
  EXPECT_FALSE(bg.running());
  EXPECT_EQ(s.history().size(), 2u);
}

// Undo, redo and jumps walked on the worker: the document the session ends with is the one the synchronous
// History::jump_to gives (same objects, same mesh bits), the session log gets one edit.undo / edit.redo line a step,
// the Log names the move; a cancelled walk changes nothing, and other changes are refused while it runs.
TEST_F(BackgroundCommandTest, HistoryMovesOnTheWorkerAreTheSynchronousOnes) {
  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.execute(test::kTeapot));
  ASSERT_TRUE(s.execute(test::kBox));
  editor::BackgroundCommand bg(s);
  ASSERT_TRUE(bg.start(fill_line(), "Filling teapot with thorn", "Fill"));
  bg.wait();
  ASSERT_TRUE(bg.finish());
  ASSERT_EQ(s.history().applied(), 3u);
  const auto layer = s.scene().find("teapot")->ddm_layers.at(0);

  ASSERT_TRUE(bg.start_history(0));
  EXPECT_TRUE(bg.running());
  EXPECT_FALSE(s.execute(test::kBox)) << "refused while the history moves";
  EXPECT_FALSE(bg.start_history(1)) << "one move at a time";
  bg.wait();
  ASSERT_TRUE(bg.finish());
  EXPECT_EQ(s.history().applied(), 0u);
  EXPECT_TRUE(s.scene().objects().empty());
  EXPECT_TRUE(logged("History: 3 steps back"));
  EXPECT_EQ(last_line(dir_ / "session.jsonl"), R"({"cmd":"edit.undo"})");

  ASSERT_TRUE(bg.start_history(1));  // a redo
  bg.wait();
  ASSERT_TRUE(bg.finish());
  EXPECT_TRUE(logged("Redo "));
  ASSERT_TRUE(bg.start_history(3));
  bg.wait();
  ASSERT_TRUE(bg.finish());
  ASSERT_EQ(s.history().applied(), 3u);
  EXPECT_EQ(s.scene().find("teapot")->ddm_layers.at(0), layer) << "the redo swaps the built layer back in";

  core::Scene sync;
  editor::History history(sync);
  const core::CommandContext ctx{fs::current_path(), {}};
  for (const nlohmann::json& l : {test::kTeapot, test::kBox, fill_line()})
    history.execute(editor::CommandRegistry::builtin().parse(l, ctx));
  history.jump_to(0);
  history.jump_to(3);
  ASSERT_EQ(s.scene().objects().size(), sync.objects().size());
  for (std::size_t i = 0; i < sync.objects().size(); ++i) {
    const core::SceneObject& a = s.scene().objects()[i];
    const core::SceneObject& b = sync.objects()[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_TRUE(same_bits(a.world_mesh->positions, b.world_mesh->positions)) << a.name;
  }

  // A cancel (before or after the walk finished) keeps the document, the position and the log as they were.
  const std::size_t lines = test::line_count(dir_ / "session.jsonl");
  ASSERT_TRUE(bg.start_history(0));
  bg.cancel();
  bg.wait();
  EXPECT_FALSE(bg.finish());
  EXPECT_EQ(s.history().applied(), 3u);
  EXPECT_EQ(s.scene().objects().size(), 2u);
  EXPECT_EQ(test::line_count(dir_ / "session.jsonl"), lines);
  EXPECT_TRUE(logged("History jump cancelled: the scene is unchanged"));
  EXPECT_FALSE(bg.start_history(3)) << "nothing to move";
}

// Open with its replay on the worker: the document becomes the opened log exactly as the synchronous Open makes it
// (same history, same meshes), the callback runs after; a cancel, a failing log and a missing file keep the document.
TEST_F(BackgroundCommandTest, OpenOnTheWorkerIsTheSynchronousOpen) {
  const fs::path log = test::log_path("ddm_follow.jsonl");
  editor::EditorSession sync(messages_);
  sync.start(false);
  ASSERT_TRUE(sync.open(log));

  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.execute(test::kTeapot));
  editor::BackgroundCommand bg(s);
  bool called = false;
  ASSERT_TRUE(bg.start_open(log, [&] { called = true; }));
  EXPECT_FALSE(s.execute(test::kBox)) << "refused while the log opens";
  bg.wait();
  EXPECT_GE(bg.progress(), 0.8) << "progress by log line";
  ASSERT_TRUE(bg.finish());
  EXPECT_TRUE(called);
  EXPECT_EQ(s.document(), sync.document());
  ASSERT_EQ(s.history().size(), sync.history().size());
  for (std::size_t i = 0; i < s.history().size(); ++i)
    EXPECT_EQ(s.history().at(i).to_json().dump(), sync.history().at(i).to_json().dump());
  ASSERT_EQ(s.scene().objects().size(), sync.scene().objects().size());
  for (std::size_t i = 0; i < s.scene().objects().size(); ++i)
    EXPECT_TRUE(
        same_bits(s.scene().objects()[i].world_mesh->positions, sync.scene().objects()[i].world_mesh->positions))
        << s.scene().objects()[i].name;

  // Cancelled, failing, missing: the document stays.
  s.new_document();
  ASSERT_TRUE(s.execute(test::kTeapot));
  ASSERT_TRUE(bg.start_open(log, [&] { ADD_FAILURE() << "a cancelled Open calls back"; }));
  bg.cancel();
  bg.wait();
  EXPECT_FALSE(bg.finish());
  EXPECT_TRUE(logged("Open cancelled: the scene is unchanged"));
  ASSERT_EQ(s.scene().objects().size(), 1u);
  const fs::path bad = dir_ / "bad.jsonl";
  std::ofstream(bad) << test::kBox.dump() << "\n{\"cmd\":\"scene.primitive\",\"kind\":\"nothing\"}\n";
  ASSERT_TRUE(bg.start_open(bad, [] {}));
  bg.wait();
  EXPECT_FALSE(bg.finish());
  EXPECT_TRUE(logged("Open failed, the current scene is kept"));
  ASSERT_TRUE(bg.start_open(dir_ / "missing.jsonl", [] {}));
  bg.wait();
  EXPECT_FALSE(bg.finish());
  EXPECT_TRUE(logged("no such file"));
  EXPECT_EQ(s.scene().objects().size(), 1u);
  EXPECT_EQ(s.scene().objects()[0].name, "teapot");
}

// The command layer alone: a prepare whose cancel flag is set throws OperationCancelled and prepares nothing; redo
// then builds it as if prepare had never run.
TEST(DdmFillPrepare, CancelledPrepareThrowsAndRedoStillBuilds) {
  core::Scene scene;
  editor::History history(scene);
  const core::CommandContext ctx{fs::current_path(), {}};
  history.execute(editor::CommandRegistry::builtin().parse(test::kTeapot, ctx));
  core::CommandPtr cmd = editor::CommandRegistry::builtin().parse(fill_line(), ctx);
  ASSERT_TRUE(cmd->preparable());
  std::atomic<bool> cancel{true};
  core::ProgressSink sink;
  sink.cancel = &cancel;
  EXPECT_THROW(cmd->prepare(scene, sink), core::OperationCancelled);
  EXPECT_TRUE(scene.find("teapot")->ddm_layers.empty());
  history.execute(std::move(cmd));
  EXPECT_FALSE(scene.find("teapot")->ddm_layers.empty());
}

}  // namespace
