// The editor session's log and crash recovery, and the Sketch tool's stroke in a session: New/Open keep the crash
// log aside and never drop the scene for a malformed file, crash recovery never loses the only copy of a log and
// asks until it is answered, a crashed second editor is offered recovery (a live one is left alone), log write
// failures are reported, a stroke uses the camera at mouse-down, and objects hidden in the viewport (object.visibility)
// do not catch placement rays.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "core/commands/place_sketch.h"
#include "core/params/codecs.h"
#include "editor/commands/command_registry.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/sketch_tool.h"
#include "session_test_util.h"
#include "stroke_gesture.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using SessionRecovery = test::StateDirTest;
using test::crash_with, test::kBox, test::kTeapot, test::line_count;

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A pid that belonged to a process which has exited.
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return long(child);
}

}  // namespace

// New keeps the previous session log aside instead of truncating it.
TEST_F(SessionRecovery, NewDocumentRenamesTheSessionLogAside) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot, kBox}));
  s.new_document();
  EXPECT_EQ(line_count(dir_ / "session.prev.jsonl"), 2u);
  EXPECT_EQ(line_count(dir_ / "session.jsonl"), 0u);
  ASSERT_TRUE(s.execute(kTeapot));
  EXPECT_EQ(line_count(dir_ / "session.jsonl"), 1u);
  s.finish();
}

// A malformed log is rejected before the current scene is dropped; the crash log is untouched.
TEST_F(SessionRecovery, MalformedOpenKeepsTheSceneAndTheLog) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot}));
  const fs::path bad = dir_ / "bad.jsonl";
  std::ofstream(bad) << kBox.dump() << "\n{\"cmd\":\"scene.prim\n";
  const std::size_t errors = messages_.error_count();
  EXPECT_FALSE(s.open(bad));
  EXPECT_EQ(messages_.error_count(), errors + 1);
  EXPECT_TRUE(logged("bad.jsonl:2")) << "the error names the file and line";
  EXPECT_EQ(s.scene().objects().size(), 1u);
  EXPECT_NE(s.scene().find("teapot"), nullptr);
  EXPECT_EQ(s.history().applied(), 1u);
  EXPECT_TRUE(s.modified());
  EXPECT_EQ(line_count(dir_ / "session.jsonl"), 1u);
  EXPECT_FALSE(fs::exists(dir_ / "session.prev.jsonl"));
  s.finish();
}

// A good Open restarts the session log with the old one kept aside.
TEST_F(SessionRecovery, OpenKeepsThePreviousSessionLogAside) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot}));
  const fs::path good = dir_ / "good.jsonl";
  std::ofstream(good) << kBox.dump() << "\n";
  ASSERT_TRUE(s.open(good));
  EXPECT_EQ(s.scene().objects().size(), 1u);
  EXPECT_NE(s.scene().find("crate"), nullptr);
  EXPECT_EQ(line_count(dir_ / "session.prev.jsonl"), 1u);
  s.finish();
}

// If the unfinished log cannot be copied aside, it is left as it is and this run logs elsewhere.
TEST_F(SessionRecovery, FailedAsideCopyLeavesTheOnlyLogAlone) {
  crash_with({kTeapot, kBox});
  const std::string before = read_all(dir_ / "session.jsonl");
  fs::create_directories(dir_ / "session.recovered.jsonl.tmp");  // write_log_atomic cannot create its temp file
  {
    editor::EditorSession s(messages_);
    EXPECT_FALSE(s.start(true));
    EXPECT_TRUE(logged("cannot keep the unfinished session's log"));
    ASSERT_TRUE(s.execute(kTeapot));
    EXPECT_EQ(read_all(dir_ / "session.jsonl"), before) << "the only copy must not be truncated";
    const fs::path own = dir_ / ("session-" + std::to_string(::getpid()) + ".jsonl");
    EXPECT_EQ(line_count(own), 1u);
    s.finish();
    EXPECT_FALSE(fs::exists(dir_ / ("session-" + std::to_string(::getpid()) + ".lock")));
  }
  fs::remove_all(dir_ / "session.recovered.jsonl.tmp");
  editor::EditorSession next(messages_);
  const auto offer = next.start(true);
  ASSERT_TRUE(offer) << "the next start offers it again";
  EXPECT_EQ(offer->commands, 2u);
  next.finish();
}

// An unanswered offer's log is never overwritten by the next crash; the question stays open until the
// replay has run.
TEST_F(SessionRecovery, UnansweredOfferIsNotOverwritten) {
  crash_with({kTeapot});
  {
    editor::EditorSession asked(messages_);
    const auto offer = asked.start(true);
    ASSERT_TRUE(offer);
    EXPECT_EQ(offer->log, dir_ / "session.recovered.jsonl");
    ASSERT_TRUE(asked.execute(kBox));
    ASSERT_TRUE(asked.execute({{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "b2"}}));
  }  // dies with its own commands before answering
  const std::string first = read_all(dir_ / "session.recovered.jsonl");
  editor::EditorSession s(messages_);
  const auto offer = s.start(true);
  ASSERT_TRUE(offer);
  EXPECT_EQ(read_all(dir_ / "session.recovered.jsonl"), first) << "the unanswered log must survive";
  EXPECT_NE(offer->log, dir_ / "session.recovered.jsonl");
  EXPECT_EQ(offer->commands, 2u);
  EXPECT_TRUE(fs::exists(dir_ / "session.recover-pending"));
  ASSERT_TRUE(s.recover(*offer));
  EXPECT_EQ(s.scene().objects().size(), 2u);
  EXPECT_FALSE(fs::exists(dir_ / "session.recover-pending")) << "answered once the replay has run";
  s.finish();
}

// A crashed second editor (session-<pid>.jsonl + .lock, pid dead) is offered for recovery.
TEST_F(SessionRecovery, CrashedSecondInstanceIsOffered) {
  fs::create_directories(dir_);
  const long pid = dead_pid();
  const fs::path log = dir_ / ("session-" + std::to_string(pid) + ".jsonl");
  const fs::path lock = dir_ / ("session-" + std::to_string(pid) + ".lock");
  std::ofstream(log) << kTeapot.dump() << "\n" << kBox.dump() << "\n";
  std::ofstream(lock) << pid << "\n";
  editor::EditorSession s(messages_);
  const auto offer = s.start(true);
  ASSERT_TRUE(offer);
  EXPECT_EQ(offer->commands, 2u);
  EXPECT_FALSE(fs::exists(lock));
  ASSERT_TRUE(s.recover(*offer));
  EXPECT_EQ(s.scene().objects().size(), 2u);
  s.finish();
  editor::EditorSession next(messages_);
  EXPECT_FALSE(next.start(true)) << "offered once";
  next.finish();
}

// A live second editor's files are left alone.
TEST_F(SessionRecovery, LiveSecondInstanceIsNotTouched) {
  fs::create_directories(dir_);
  const long pid = long(::getppid());  // alive
  const fs::path log = dir_ / ("session-" + std::to_string(pid) + ".jsonl");
  const fs::path lock = dir_ / ("session-" + std::to_string(pid) + ".lock");
  std::ofstream(log) << kTeapot.dump() << "\n";
  std::ofstream(lock) << pid << "\n";
  editor::EditorSession s(messages_);
  EXPECT_FALSE(s.start(true));
  EXPECT_TRUE(fs::exists(lock));
  EXPECT_EQ(line_count(log), 1u);
  s.finish();
}

// CommandLog::append reports write failures; History reports the first one once.
TEST_F(SessionRecovery, LogWriteFailuresAreReported) {
  ASSERT_TRUE(fs::exists("/dev/full")) << "this test writes to /dev/full (present on every Linux)";
  editor::CommandLog log("/dev/full", true);
  EXPECT_FALSE(log.append(kTeapot));
  EXPECT_NE(log.error().find("/dev/full"), std::string::npos) << log.error();

  core::Scene scene;
  editor::History h(scene);
  std::vector<std::string> errors;
  h.on_log_error = [&](const std::string& e) { errors.push_back(e); };
  h.set_log(&log);
  core::CommandContext ctx;
  h.execute(editor::CommandRegistry::builtin().parse(kTeapot, ctx));
  h.undo();
  h.redo();
  EXPECT_EQ(h.applied(), 1u) << "the command itself stands";
  ASSERT_EQ(errors.size(), 1u) << "only the first failure is reported";
  EXPECT_NE(errors[0].find("/dev/full"), std::string::npos);
}

// The session routes a failing log to the Log panel as a warning.
TEST_F(SessionRecovery, SessionWarnsWhenItsLogFails) {
  ASSERT_TRUE(fs::exists("/dev/full")) << "this test writes to /dev/full (present on every Linux)";
  editor::EditorSession s(messages_);
  s.start(false);
  editor::CommandLog full("/dev/full", true);
  s.history().set_log(&full);
  ASSERT_TRUE(s.execute(kTeapot));
  EXPECT_TRUE(logged("session log:")) << "the failure reaches the Log panel";
  s.history().set_log(nullptr);
  s.finish();
}

// The stroke uses the camera at mouse-down, and an object hidden in the viewport lets the rays pass (the hiding is in
// the log, so the line needs no "ignore").
TEST_F(SessionRecovery, StrokeKeepsItsMouseDownCameraAndIgnoresHidden) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot, kBox}));
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "veil"}, {"translate", {0, 0, 3}}}));
  core::Camera view = test::framed_view(s.scene(), "teapot");
  ASSERT_TRUE(s.execute({{"cmd", "object.visibility"}, {"object", "veil"}, {"viewport", false}}));
  const core::Camera at_press = view;
  test::SketchToolRig rig(s, view);
  editor::SketchTool& tool = rig.tool;
  rig.press_stroke();
  EXPECT_TRUE(tool.owns_mouse()) << "the editor must not navigate while a stroke is drawn";
  rig.drag_stroke();
  view.eye += glm::dvec3(0.5, 0.3, 0.0);  // the view changes before mouse-up (resize, follow, ...)
  rig.release_stroke();
  EXPECT_FALSE(tool.owns_mouse());
  ASSERT_EQ(s.history().applied(), 5u) << (messages_.messages().empty() ? "" : messages_.messages().back().text);
  const nlohmann::json line = s.history().at(4).to_json();
  const core::Camera used = core::camera_schema().parse(line.at("camera"));
  EXPECT_EQ(used.eye, at_press.eye) << "the stroke's pixels belong to the view at mouse-down";
  EXPECT_FALSE(line.contains("ignore"));
  const core::Aabb veil = core::mesh_bounds(*s.scene().find("veil")->world_mesh);
  const core::PlacementRecord& placed = *s.scene().find("crate")->placement;
  for (const glm::dvec3& p : placed.contact_points)
    EXPECT_FALSE(glm::all(glm::greaterThan(p, veil.lo - 1e-9)) && glm::all(glm::lessThan(p, veil.hi + 1e-9)))
        << "a placement ray stopped on the hidden veil";

  // A parameter re-run keeps both.
  core::PlaceSketchParams p = tool.params();
  p.height *= 2;
  tool.set_params(p, rig.ctx);
  const nlohmann::json rerun = s.history().at(4).to_json();
  EXPECT_FALSE(rerun.contains("ignore"));
  EXPECT_EQ(rerun["camera"], line["camera"]);
  s.finish();
}

// "ignore" parses, round-trips only when non-empty, and names the field in its errors.
TEST(PlaceSketchIgnore, ParseAndSerialise) {
  nlohmann::json j = {
      {"cmd", "place.sketch"}, {"object", "a"}, {"stroke", {{0, 0}, {10, 0}}}, {"width", 0.1}, {"height", 0.1}};
  core::CommandContext ctx;
  EXPECT_FALSE(core::PlaceSketchCommand::parse(j, ctx)->to_json().contains("ignore"));
  j["ignore"] = {"b", "c"};
  const auto cmd = core::PlaceSketchCommand::parse(j, ctx);
  EXPECT_EQ(cmd->to_json()["ignore"], nlohmann::json::array({"b", "c"}));
  for (const nlohmann::json& bad : {nlohmann::json("b"), nlohmann::json::array({"b", 3})}) {
    j["ignore"] = bad;
    try {
      core::PlaceSketchCommand::parse(j, ctx);
      ADD_FAILURE() << "accepted ignore=" << bad.dump();
    } catch (const core::CommandError& e) {
      EXPECT_EQ(e.field(), "ignore");
      EXPECT_NE(std::string(e.what()).find("field 'ignore'"), std::string::npos) << e.what();
    }
  }
}

// An ignored object does not catch the placement rays.
TEST_F(SessionRecovery, IgnoredObjectsDoNotCatchRays) {
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {kTeapot, kBox}));
  const core::Camera view = test::framed_view(s.scene(), "teapot");
  const std::vector<glm::dvec2> stroke = test::shallow_arc(330);
  core::PlaceSketchParams params;
  params.object = "crate";
  ASSERT_TRUE(s.execute(editor::place_sketch_line(params, stroke, view)));
  ASSERT_TRUE(s.undo());
  // With the teapot ignored nothing else is under the stroke: every ray misses and the command is refused.
  const std::size_t errors = messages_.error_count();
  EXPECT_FALSE(s.execute(editor::place_sketch_line(params, stroke, view, {"teapot"})));
  EXPECT_EQ(messages_.error_count(), errors + 1);
  EXPECT_FALSE(s.scene().find("crate")->ffd) << "the scene is unchanged";
  s.finish();
}

// write_log_atomic still writes and replaces (the folder fsync is best effort).
TEST_F(SessionRecovery, AtomicWriteReplaces) {
  fs::create_directories(dir_);
  const fs::path p = dir_ / "x.jsonl";
  editor::write_log_atomic(p, {kTeapot});
  editor::write_log_atomic(p, {kTeapot, kBox});
  EXPECT_EQ(line_count(p), 2u);
  EXPECT_FALSE(fs::exists(dir_ / "x.jsonl.tmp"));
}
