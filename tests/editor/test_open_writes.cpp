// Opening a log never writes files (docs/decisions.md): File ▸ Open, crash recovery, undo / redo and History jumps
// re-create the scene but leave volume.export's files and anim.record's frames alone; the History shows those entries
// "not written again" and Run again writes them, the bytes a headless replay writes. Headless replay keeps writing.
// The Record dialog's camera choice goes into anim.record's "camera" and the recorder renders from it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/commands/anim_record.h"
#include "core/commands/file_output.h"
#include "editor/animation_ui.h"
#include "editor/commands/command_log.h"
#include "editor/replay/record.h"
#include "headless_imgui.h"
#include "tests/editor/session_test_util.h"
#include "ui/record_dialog.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_lines(const fs::path& path, const std::vector<nlohmann::json>& lines) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  for (const auto& l : lines) out << l.dump() << "\n";
}

const nlohmann::json kCamera = {{"cmd", "camera.set"}, {"eye", {0.0, -110.0, 70.0}},
                                {"target", {0, 0, 0}}, {"up", {0, 0, 1}},
                                {"fov_deg", 40.0},     {"viewport", {160, 120}}};

// A torus volume with silhouettes, exported as SVG (`svg`) and as glTF lines (`glb`), relative to the log's folder.
std::vector<nlohmann::json> export_lines(const std::string& svg, const std::string& glb) {
  return {{{"cmd", "volume.load"}, {"analytic", "torus"}, {"name", "torus"}, {"iso", 0.0}},
          {{"cmd", "volume.silhouettes"}, {"object", "torus"}, {"style", "plain"}, {"hidden", "remove"}},
          kCamera,
          {{"cmd", "volume.export"}, {"object", "torus"}, {"what", "silhouettes"}, {"path", svg}},
          {{"cmd", "volume.export"}, {"object", "torus"}, {"what", "silhouettes"}, {"path", glb}}};
}

// A teapot on a 3-frame timeline, recorded (frames 1-2, 48×32, PNG only) into `out` next to the log.
std::vector<nlohmann::json> record_lines(const std::string& out) {
  return {{{"cmd", "anim.timeline"}, {"fps", 24}, {"start", 1}, {"end", 3}},
          {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}},
          {{"cmd", "camera.set"},
           {"eye", {0, 2.6, 3.2}},
           {"target", {0, 0.2, 0}},
           {"up", {0, 1, 0}},
           {"fov_deg", 40},
           {"viewport", {48, 32}}},
          {{"cmd", "anim.record"},
           {"out", out},
           {"format", "png"},
           {"frames", {1, 2}},
           {"glb", false},
           {"mp4", false},
           {"width", 48},
           {"height", 32}}};
}

// A file's bytes and modification time, to prove it was not touched.
struct FileState {
  std::string bytes;
  fs::file_time_type mtime;
};
FileState state_of(const fs::path& p) { return {read_all(p), fs::last_write_time(p)}; }

// Every file under `dir` whose extension is `ext`.
std::vector<fs::path> files_with(const fs::path& dir, const std::string& ext) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ext) found.push_back(it->path());
  return found;
}

class OpenWrites : public test::StateDirTest {
 protected:
  void SetUp() override {
    StateDirTest::SetUp();
    work_ = dir_ / "work";
    fs::create_directories(work_);
  }
  fs::path work_;
};

TEST_F(OpenWrites, OpenLeavesExportsAloneAndRunAgainWritesTheReplayedBytes) {
  const fs::path log = work_ / "skull.jsonl";
  write_lines(log, export_lines("torus.svg", "torus_lines.glb"));
  // The artist's SVG, edited by hand since the export, an hour old; the glb was deleted.
  { std::ofstream(work_ / "torus.svg") << "<svg><!-- retouched by hand --></svg>\n"; }
  fs::last_write_time(work_ / "torus.svg", fs::file_time_type::clock::now() - std::chrono::hours(1));
  const FileState before = state_of(work_ / "torus.svg");

  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.open(log));
  ASSERT_EQ(s.history().size(), 5u);
  EXPECT_EQ(state_of(work_ / "torus.svg").bytes, before.bytes) << "Open rewrote the exported SVG";
  EXPECT_EQ(state_of(work_ / "torus.svg").mtime, before.mtime);
  EXPECT_FALSE(fs::exists(work_ / "torus_lines.glb")) << "Open wrote a deleted export again";
  EXPECT_TRUE(s.scene().find_volume("torus")->silhouettes) << "the scene is re-created: the volume keeps them";

  ui::HistoryView v = s.history_view();
  ASSERT_EQ(v.not_written.size(), 5u);
  EXPECT_EQ(v.not_written, (std::vector<bool>{false, false, false, true, true}));
  EXPECT_EQ(fs::path(v.paths[3]), fs::weakly_canonical(work_ / "torus.svg"));
  EXPECT_EQ(ui::not_written_label(v.labels[3]), "Export silhouettes of 'torus' \xE2\x80\x94 not written again");

  // Undo to the start, redo to the end, History clicks in between: no file is written.
  for (std::size_t n : {0u, 5u, 3u, 4u, 5u}) ASSERT_TRUE(s.jump_to(n));
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(state_of(work_ / "torus.svg").bytes, before.bytes) << "a History move rewrote the SVG";
  EXPECT_EQ(state_of(work_ / "torus.svg").mtime, before.mtime);
  EXPECT_FALSE(fs::exists(work_ / "torus_lines.glb"));

  // Run again on the glb entry: written, the bytes headless replay writes for that line; the SVG is still left alone.
  const std::size_t applied = s.history().applied();
  ASSERT_TRUE(s.run_again(4));
  EXPECT_EQ(s.history().applied(), applied) << "Run again is no new history step";
  EXPECT_EQ(s.history().size(), 5u);
  ASSERT_TRUE(fs::exists(work_ / "torus_lines.glb"));
  EXPECT_TRUE(logged("wrote " + fs::weakly_canonical(work_ / "torus_lines.glb").string()));
  EXPECT_EQ(state_of(work_ / "torus.svg").bytes, before.bytes);
  v = s.history_view();
  EXPECT_EQ(v.not_written, (std::vector<bool>{false, false, false, true, false}));

  core::Scene replayed;
  editor::History h(replayed);
  const fs::path out = dir_ / "replay_out";
  ASSERT_TRUE(editor::replay_lines(h, log, {}, out).ok);
  ASSERT_TRUE(fs::exists(out / "torus_lines.glb")) << "headless replay keeps writing under --out";
  ASSERT_TRUE(fs::exists(out / "torus.svg"));
  EXPECT_EQ(read_all(work_ / "torus_lines.glb"), read_all(out / "torus_lines.glb"));

  // The SVG too, now on purpose.
  ASSERT_TRUE(s.run_again(3));
  EXPECT_EQ(read_all(work_ / "torus.svg"), read_all(out / "torus.svg"));
  EXPECT_NE(read_all(work_ / "torus.svg").find("<path"), std::string::npos);
}

TEST_F(OpenWrites, UndoAndRedoOfAnExportNeverRewriteItsFile) {
  editor::EditorSession s(messages_);
  s.start(false);
  for (const auto& l : export_lines("torus.svg", "torus_lines.glb")) ASSERT_TRUE(s.execute(l, work_, work_));
  ASSERT_TRUE(fs::exists(work_ / "torus.svg")) << "an export the artist runs writes its file";
  EXPECT_FALSE(s.history_view().not_written[3]);
  { std::ofstream(work_ / "torus.svg") << "mine\n"; }
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(read_all(work_ / "torus.svg"), "mine\n") << "undo never touches a file";
  ASSERT_TRUE(s.redo());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(read_all(work_ / "torus.svg"), "mine\n") << "redo of an export is not exporting again";
}

TEST_F(OpenWrites, RecoveryWritesNothing) {
  {
    ui::MessageLog m;
    editor::EditorSession crashed(m);
    crashed.start(true);
    for (const auto& l : export_lines("torus.svg", "torus_lines.glb")) ASSERT_TRUE(crashed.execute(l, work_, work_));
    const auto rec = record_lines((work_ / "frames").string());
    ASSERT_TRUE(crashed.execute(rec[0]));
    ASSERT_TRUE(crashed.execute(rec[3])) << "logged; the editor's Record button would record it now";
  }  // dies without finish(): its lock and log stay
  ASSERT_TRUE(fs::exists(work_ / "torus.svg"));
  fs::remove(work_ / "torus.svg");
  const FileState glb = state_of(work_ / "torus_lines.glb");

  editor::EditorSession s(messages_);
  const auto offer = s.start(true);
  ASSERT_TRUE(offer);
  ASSERT_TRUE(s.recover(*offer));
  EXPECT_TRUE(s.scene().find_volume("torus"));
  EXPECT_FALSE(fs::exists(work_ / "torus.svg")) << "recovery wrote a deleted export again";
  EXPECT_EQ(state_of(work_ / "torus_lines.glb").bytes, glb.bytes);
  EXPECT_EQ(state_of(work_ / "torus_lines.glb").mtime, glb.mtime);
  EXPECT_TRUE(files_with(dir_, ".svg").empty()) << "nothing written next to the recovered log either";
  EXPECT_FALSE(fs::exists(work_ / "frames")) << "recovery recorded the animation";
  const ui::HistoryView v = s.history_view();
  ASSERT_GE(v.not_written.size(), 5u);
  EXPECT_TRUE(v.not_written[3] && v.not_written[4]);
  ASSERT_EQ(v.outputs.size(), 1u);
  EXPECT_TRUE(v.outputs[0].not_written);
}

TEST_F(OpenWrites, OpenedRecordingIsNotRecordedUntilRunAgain) {
  const fs::path log = work_ / "anim.jsonl";
  write_lines(log, record_lines("frames"));
  editor::EditorSession s(messages_);
  s.start(false);
  ASSERT_TRUE(s.open(log));
  EXPECT_FALSE(fs::exists(work_ / "frames")) << "Open recorded the animation again";
  ui::HistoryView v = s.history_view();
  ASSERT_EQ(v.labels.size(), 3u) << "anim.record is no undo step";
  ASSERT_EQ(v.outputs.size(), 1u) << "but the History shows it";
  EXPECT_EQ(v.outputs[0].after, 3u);
  EXPECT_EQ(v.outputs[0].label, "Record frames 1-2");
  EXPECT_TRUE(v.outputs[0].not_written);
  EXPECT_TRUE(v.outputs[0].can_run_again);
  // The session log keeps the line in its place (a crash now recovers it, again not recorded).
  std::vector<std::string> cmds;
  for (const auto& line : editor::read_log(dir_ / "session.jsonl")) cmds.push_back(line.json.value("cmd", ""));
  EXPECT_EQ(cmds, (std::vector<std::string>{"anim.timeline", "scene.primitive", "camera.set", "anim.record"}));

  // Moving through the History records nothing either; then the scene changes (the teapot is removed).
  ASSERT_TRUE(s.jump_to(0));
  ASSERT_TRUE(s.jump_to(3));
  ASSERT_TRUE(s.execute({{"cmd", "scene.remove"}, {"name", "t"}}));
  EXPECT_FALSE(fs::exists(work_ / "frames"));

  // Run again records the frames from the scene it ran on (with the teapot), into the line's folder.
  editor::AnimationUi anim(s, messages_);
  ASSERT_TRUE(anim.run_again(0)) << (messages_.messages().empty() ? "" : messages_.messages().back().text);
  test::HeadlessImGui gui;
  for (int f = 0; anim.recording() && f < 10; ++f) gui.step({0, 0}, false, [&] { anim.draw_record_ui({}); });
  EXPECT_FALSE(anim.recording());
  ASSERT_TRUE(fs::exists(work_ / "frames" / "frame_0001.png"));
  ASSERT_TRUE(fs::exists(work_ / "frames" / "frame_0002.png"));
  EXPECT_FALSE(fs::exists(work_ / "frames" / "frame_0003.png"));
  EXPECT_FALSE(s.history_view().outputs[0].not_written);

  // Byte for byte what headless replay records for that line.
  core::Scene replayed;
  editor::History h(replayed);
  ASSERT_TRUE(editor::replay_lines(h, log).ok);
  const auto* cmd = dynamic_cast<const core::AnimRecordCommand*>(h.outputs().at(0).command.get());
  ASSERT_TRUE(cmd);
  editor::RecordOptions ro;
  ro.out_dir = dir_ / "replayed_frames";
  ro.frame_first = 1;
  ro.frame_last = 2;
  ro.width = 48;
  ro.height = 32;
  ro.glb = ro.mp4 = false;
  editor::record_frames(replayed, ro);
  EXPECT_EQ(read_all(work_ / "frames" / "frame_0002.png"), read_all(dir_ / "replayed_frames" / "frame_0002.png"));
}

TEST_F(OpenWrites, RecordDialogRecordsTheChosenCamera) {
  core::Scene scene;
  scene.timeline.frame_start = 1;
  scene.timeline.frame_end = 2;
  core::Camera view;
  view.eye = {2.5, 1.0, 0.5};
  view.target = {0, 0.2, 0};
  view.up = {0, 1, 0};
  view.fov_deg = 35;
  view.viewport = {64, 48};
  ui::RecordDialogState d;
  d.out_dir = (dir_ / "rec").string();
  ui::open_record_dialog(d, scene.timeline, 64, 48, scene, view);
  EXPECT_EQ(d.camera, ui::kCurrentView) << "no scene camera: the view is what the artist expects";
  nlohmann::json line = ui::record_line(d);
  ASSERT_TRUE(line.contains("camera"));
  EXPECT_EQ(line["camera"]["eye"], nlohmann::json({2.5, 1.0, 0.5}));
  d.camera = ui::kSceneCamera;
  EXPECT_FALSE(ui::record_line(d).contains("camera")) << "the scene camera is anim.record's default";

  ui::RecordDialogState d2;
  scene.camera_set = true;
  ui::open_record_dialog(d2, scene.timeline, 64, 48, scene, view);
  EXPECT_EQ(d2.camera, ui::kSceneCamera) << "a scene camera (the log's camera.set) is preset";

  // The camera field parses, round-trips, and the recorder renders from it: the frame is the one the scene camera
  // gives when camera.set is that view, and differs from the default camera's.
  editor::EditorSession s(messages_);
  ASSERT_TRUE(test::start_with(s, {{{"cmd", "anim.timeline"}, {"fps", 24}, {"start", 1}, {"end", 2}},
                                   {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}}}));
  d.camera = ui::kCurrentView;
  d.frames[0] = d.frames[1] = 1;
  d.size[0] = 64;
  d.size[1] = 48;
  d.glb = d.mp4 = false;
  editor::AnimationUi anim(s, messages_);
  ASSERT_TRUE(anim.start_recording(ui::record_line(d)));
  test::HeadlessImGui gui;
  for (int f = 0; anim.recording() && f < 10; ++f) gui.step({0, 0}, false, [&] { anim.draw_record_ui({}); });
  const auto& rec = dynamic_cast<const core::AnimRecordCommand&>(s.history().last_executed());
  ASSERT_TRUE(rec.request().camera);
  EXPECT_EQ(rec.to_json()["camera"]["fov_deg"], 35.0);
  const std::string chosen = read_all(dir_ / "rec" / "frame_0001.png");
  ASSERT_FALSE(chosen.empty());

  editor::RecordOptions ro;
  ro.out_dir = dir_ / "default_cam";
  ro.frame_first = ro.frame_last = 1;
  ro.width = 64;
  ro.height = 48;
  ro.glb = ro.mp4 = false;
  editor::record_frames(s.scene(), ro);
  EXPECT_NE(read_all(dir_ / "default_cam" / "frame_0001.png"), chosen) << "the default camera is another view";
  core::Scene with_camera = s.scene();
  with_camera.camera = view;
  with_camera.camera_set = true;
  ro.out_dir = dir_ / "scene_cam";
  editor::record_frames(with_camera, ro);
  EXPECT_EQ(read_all(dir_ / "scene_cam" / "frame_0001.png"), chosen);
}

}  // namespace
