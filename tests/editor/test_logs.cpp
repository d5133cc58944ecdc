// Replay tests: the logs in tests/logs/ run headlessly through the same registry and history as the editor.
#include <gtest/gtest.h>

#include <filesystem>

#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "tests/editor/session_test_util.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using test::logs_dir;

using test::BadLogCase;

class BadLog : public ::testing::TestWithParam<BadLogCase> {};

TEST_P(BadLog, StopsWithFileLineFieldAndLeavesEarlierLines) {
  const BadLogCase c = GetParam();
  core::Scene scene;
  editor::History history(scene);
  editor::ReplayResult r;
  ASSERT_NO_FATAL_FAILURE(test::expect_stops_at(history, logs_dir() / c.file, c, r));
  // Every line before the bad one is in effect, the bad one left no trace.
  EXPECT_EQ(history.applied(), r.records.size() - 1);
}

INSTANTIATE_TEST_SUITE_P(
    Logs, BadLog,
    ::testing::Values(BadLogCase{"bad_missing_file.jsonl", 3, "path", "does_not_exist.obj"},
                      BadLogCase{"bad_unsupported_file.jsonl", 1, "path", "xyz"},
                      BadLogCase{"bad_corrupt_file.jsonl", 1, "path", "corrupt.ply"},
                      BadLogCase{"bad_nan_vertices.jsonl", 1, "path", "finite"},
                      BadLogCase{"bad_empty_mesh.jsonl", 1, "path", "empty"},
                      BadLogCase{"bad_unknown_command.jsonl", 2, "cmd", "scene.explode"},
                      BadLogCase{"bad_malformed_json.jsonl", 2, "", "malformed JSON"},
                      BadLogCase{"bad_wrong_field_type.jsonl", 1, "scale", "expected a number"},
                      BadLogCase{"bad_unknown_kind.jsonl", 1, "kind", "dodecahedron"},
                      BadLogCase{"bad_duplicate_name.jsonl", 2, "name", "already exists"},
                      BadLogCase{"bad_ddm_fill_counts.jsonl", 2, "counts", "empty rect layout"},
                      BadLogCase{"bad_ddm_paint_radius.jsonl", 3, "radius_px", "(0, 16384]"},
                      BadLogCase{"bad_ddm_paint_miss.jsonl", 4, "stroke", "touches no visible cell"},
                      BadLogCase{"bad_ddm_layers_deform.jsonl", 7, "object", "holds tile layers (spots)"},
                      BadLogCase{"bad_ddm_remove_layer.jsonl", 5, "layer", "spots"},
                      BadLogCase{"bad_undo_nothing.jsonl", 1, "cmd", "nothing to undo"},
                      BadLogCase{"bad_stroke_one_point.jsonl", 4, "stroke", "2"},
                      BadLogCase{"bad_zero_width.jsonl", 4, "width", "width"},
                      BadLogCase{"bad_all_rays_miss.jsonl", 4, "stroke", "rays"},
                      BadLogCase{"bad_unknown_object.jsonl", 4, "object", "nobody"},
                      BadLogCase{"bad_order_above_controls.jsonl", 4, "order", "order"},
                      BadLogCase{"bad_no_camera.jsonl", 3, "camera", "camera.set"},
                      BadLogCase{"bad_too_many_controls.jsonl", 4, "controls", "256"},
                      BadLogCase{"bad_negative_seed.jsonl", 1, "seed", "out of range"},
                      BadLogCase{"bad_camera_fov.jsonl", 2, "camera.fov_deg", "fov"},
                      BadLogCase{"bad_ring_radius.jsonl", 2, "radius", "half the width"},
                      BadLogCase{"bad_volume_transfer.jsonl", 2, "transfer", "values must increase"},
                      BadLogCase{"bad_text_font.jsonl", 2, "font", "brick.obj"},
                      BadLogCase{"bad_tile_clip.jsonl", 2, "tile_clip", "a glTF file"},
                      BadLogCase{"bad_text_control.jsonl", 2, "text", "control character"},
                      BadLogCase{"bad_animate_no_ffd.jsonl", 2, "object", "no FFD lattice"},
                      BadLogCase{"bad_refine_tolerance.jsonl", 3, "tolerance", "> 0"},
                      BadLogCase{"bad_width_profile.jsonl", 4, "width_profile", "finite"},
                      BadLogCase{"bad_press_radius.jsonl", 5, "radius", "> 0"},
                      BadLogCase{"bad_keyframe_nan.jsonl", 5, "u", "expected a number"},
                      BadLogCase{"bad_timeline_fps.jsonl", 2, "fps", "[0.01, 240]"},
                      BadLogCase{"bad_empty_clip.jsonl", 2, "clip", "animates no mesh"},
                      BadLogCase{"bad_array_count.jsonl", 5, "count", "[1, 64]"},
                      BadLogCase{"bad_record_range.jsonl", 3, "frames", "outside the timeline"},
                      BadLogCase{"bad_dffd_cut_outside.jsonl", 5, "at", "inside"},
                      BadLogCase{"bad_dffd_split_box.jsonl", 4, "box", "larger than the lattice"},
                      BadLogCase{"bad_dffd_split_fold.jsonl", 4, "kernel_width", "fold-over"},
                      BadLogCase{"bad_incision_miss.jsonl", 3, "stroke", "misses the surface"},
                      BadLogCase{"bad_incision_depth.jsonl", 3, "depth", "> 0"},
                      BadLogCase{"bad_transform_scale.jsonl", 3, "scale", "(0, 1e6]"}),
    [](const auto& info) {
      std::string n = info.param.file;
      n = n.substr(4, n.size() - 4 - 6);  // strip "bad_" and ".jsonl"
      return n;
    });

TEST(GoodLogs, EveryGoodLogReplays) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(logs_dir())) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".jsonl" || name.rfind("bad_", 0) == 0) continue;
    core::Scene scene;
    editor::History history(scene);
    const auto r = editor::replay_lines(history, entry.path());
    EXPECT_TRUE(r.ok) << name << ": " << r.error;
    ++count;
  }
  EXPECT_GE(count, 2);
}

TEST(Registry, UnknownAndMissingCmd) {
  core::CommandContext ctx;
  const auto& reg = editor::CommandRegistry::builtin();
  EXPECT_THROW(reg.parse({{"name", "x"}}, ctx), core::CommandError);
  EXPECT_THROW(reg.parse({{"cmd", 3}}, ctx), core::CommandError);
  EXPECT_THROW(reg.parse(nlohmann::json::array(), ctx), core::CommandError);
  for (const char* id : {"scene.load", "scene.primitive", "scene.remove", "camera.set", "place.sketch", "lattice.ring",
                         "lattice.animate_offset", "object.transform"})
    EXPECT_NE(std::find(reg.ids().begin(), reg.ids().end(), id), reg.ids().end()) << id;
}

}  // namespace

namespace {

TEST(CommandLog, LoadLinesCarryAbsolutePathsAndSaveMakesThemRelative) {
  core::CommandContext ctx;
  ctx.base_dir = logs_dir();
  const auto cmd = editor::CommandRegistry::builtin().parse(
      nlohmann::json::parse(R"({"cmd":"scene.load","path":"data/empty.obj","name":"e"})"), ctx);
  const std::string logged = cmd->to_json().at("path");
  EXPECT_TRUE(fs::path(logged).is_absolute()) << logged;
  EXPECT_EQ(fs::path(logged), (logs_dir() / "data" / "empty.obj").lexically_normal());

  std::vector<nlohmann::json> lines = {cmd->to_json(), {{"cmd", "camera.set"}, {"path", "/not/touched"}}};
  editor::make_paths_relative(lines, logs_dir());
  EXPECT_EQ(lines[0].at("path"), "data/empty.obj");
  EXPECT_EQ(lines[1].at("path"), "/not/touched");

  // ddm.fill's tile file likewise; a generated tile is a name and stays as it is.
  const auto fill = editor::CommandRegistry::builtin().parse(
      nlohmann::json::parse(
          R"({"cmd":"ddm.fill","base":"limit","object":"o","layer":"l","tile":"data/brick.obj","layout":"rect",
                                "counts":[1,1],"height":0.1})"),
      ctx);
  EXPECT_TRUE(fs::path(fill->to_json().at("tile").get<std::string>()).is_absolute());
  std::vector<nlohmann::json> fills = {fill->to_json(), fill->to_json()};
  fills[1]["tile"] = "thorn";
  editor::make_paths_relative(fills, logs_dir());
  EXPECT_EQ(fills[0].at("tile"), "data/brick.obj");
  EXPECT_EQ(fills[1].at("tile"), "thorn");
}

TEST(CommandLog, AtomicWriteThenReadRoundTripsWithCmdFirst) {
  const fs::path dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "log_roundtrip";
  fs::create_directories(dir);
  const fs::path file = dir / "scene.jsonl";
  const std::vector<nlohmann::json> lines = {{{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "b"}},
                                             {{"cmd", "edit.undo"}}};
  editor::write_log_atomic(file, lines);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  const auto back = editor::read_log(file);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].json, lines[0]);
  EXPECT_EQ(back[0].text.rfind(R"({"cmd":"scene.primitive")", 0), 0u) << back[0].text;
  EXPECT_EQ(back[1].number, 2);
}

}  // namespace

namespace {

TEST(CommandLog, FarAwayPathsStayAbsolute) {
  std::vector<nlohmann::json> lines = {{{"cmd", "scene.load"}, {"path", "/usr/share/x/mesh.obj"}},
                                       {{"cmd", "scene.load"}, {"path", "/home/u/project/data/m.obj"}}};
  editor::make_paths_relative(lines, "/home/u/project/scenes/a/b");
  EXPECT_EQ(lines[0].at("path"), "/usr/share/x/mesh.obj");
  EXPECT_EQ(lines[1].at("path"), "/home/u/project/data/m.obj");  // three folders up: kept absolute
  std::vector<nlohmann::json> near = {{{"cmd", "scene.load"}, {"path", "/home/u/project/data/m.obj"}}};
  editor::make_paths_relative(near, "/home/u/project/scenes");
  EXPECT_EQ(near[0].at("path"), "../data/m.obj");
}

}  // namespace
