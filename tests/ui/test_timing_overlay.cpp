// The live timing overlay without a window: its key and menu toggle, the numbers it shows (means over the
// last second, the 5 s graph window, vertices per second, idle detection), the stage timings it reads from a
// command's stats(), and drawing it in a headless Dear ImGui frame (no GL needed: ImGui only builds draw lists).
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include "core/commands/command.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "headless_imgui.h"
#include "ui/frame_timings.h"
#include "ui/main_menu.h"
#include "ui/overlays.h"
#include "ui/shortcuts.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <filesystem>

using namespace trispline;

namespace {

using test::HeadlessImGui;

ui::FrameSample sample(double t, double work, double interval, double ffd, double draw, double uims, std::size_t n) {
  ui::FrameSample s;
  s.time_s = t;
  s.work_ms = work;
  s.interval_ms = interval;
  s.passes.ffd_ms = ffd;
  s.passes.draw_ms = draw;
  s.passes.ui_ms = uims;
  s.passes.ffd_vertices = n;
  return s;
}

}  // namespace

TEST(TimingOverlay, F7TogglesItAndClashesWithNoOtherShortcut) {
  using A = ui::MenuAction;
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_F7, 0}), A::ToggleTimingOverlay);
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_F7, GLFW_MOD_CONTROL}), A::None);
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_F7, GLFW_MOD_ALT}), A::None);
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_F7, GLFW_MOD_SHIFT}), A::None);
  // The existing Blender-like keys are unchanged.
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_F, 0}), A::FrameSelected);
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_Q, 0}), A::SelectTool);
  EXPECT_EQ(ui::shortcut_action({GLFW_KEY_Z, GLFW_MOD_CONTROL}), A::Undo);
  for (int key : {GLFW_KEY_F, GLFW_KEY_Q, GLFW_KEY_W, GLFW_KEY_X, GLFW_KEY_HOME, GLFW_KEY_DELETE, GLFW_KEY_F12})
    EXPECT_NE(ui::shortcut_action({key, 0}), A::ToggleTimingOverlay) << key;

  ui::ViewToggles view;
  ASSERT_TRUE(view.timing_overlay) << "on by default";
  EXPECT_TRUE(ui::apply_view_action(view, A::ToggleTimingOverlay));
  EXPECT_FALSE(view.timing_overlay);
  EXPECT_TRUE(ui::apply_view_action(view, A::ToggleTimingOverlay));
  EXPECT_TRUE(view.timing_overlay);
  EXPECT_FALSE(ui::apply_view_action(view, A::FrameAll));
  EXPECT_TRUE(view.timing_overlay);
}

TEST(TimingOverlay, DiscontinuityToggleDefaultsOnAndReachesTheRenderer) {
  ui::ViewToggles view;
  EXPECT_TRUE(ui::view_options(view).show_discontinuities);
  view.show_discontinuities = false;
  EXPECT_FALSE(ui::view_options(view).show_discontinuities);
}

TEST(TimingOverlay, FfdBackendSettingDefaultsToGlslComputeAndReachesTheRenderer) {
  ui::ViewToggles view;
  EXPECT_EQ(view.ffd_backend, core::FfdBackend::glsl_compute);
  EXPECT_EQ(ui::view_options(view).ffd_backend, core::FfdBackend::glsl_compute);
  view.ffd_backend = core::FfdBackend::cpu_fast;
  EXPECT_EQ(ui::view_options(view).ffd_backend, core::FfdBackend::cpu_fast);
  EXPECT_STREQ(ui::ffd_backend_label(core::FfdBackend::glsl_compute), "GLSL compute");
  EXPECT_STREQ(ui::ffd_backend_label(core::FfdBackend::glsl_vertex), "GLSL vertex shader");
  EXPECT_STREQ(ui::ffd_backend_label(core::FfdBackend::cpu_fast), "CPU fast");
  EXPECT_STREQ(ui::ffd_backend_label(core::FfdBackend::cpu_ref), "CPU reference");
  for (core::FfdBackend b : ui::kFfdBackendsShown) EXPECT_GT(std::string(ui::ffd_backend_tooltip(b)).size(), 20u);
}

TEST(TimingOverlay, SummaryAveragesTheLastSecond) {
  ui::TimingOverlay overlay;
  EXPECT_EQ(overlay.summary().frames, 0u);
  EXPECT_LT(overlay.summary().fps, 0.0);
  // 3 s at 50 FPS: an old slow second, then two seconds of steady frames.
  for (int i = 0; i < 150; ++i) {
    const double t = 100.0 + i * 0.02;
    if (i < 50)
      overlay.add_frame(sample(t, 40, 20, 30, 30, 30, 1000));
    else
      overlay.add_frame(sample(t, 8, 20, 2, 3, 1, 100000));
  }
  const auto s = overlay.summary();
  EXPECT_GE(s.frames, 50u);
  EXPECT_LE(s.frames, 52u);
  EXPECT_NEAR(s.fps, 50.0, 1e-9);
  EXPECT_NEAR(s.frame_ms, 8.0, 1e-9);
  EXPECT_NEAR(s.ffd_ms, 2.0, 1e-9);
  EXPECT_NEAR(s.draw_ms, 3.0, 1e-9);
  EXPECT_NEAR(s.ui_ms, 1.0, 1e-9);
  EXPECT_NEAR(s.ffd_vertices, 100000.0, 1e-6);
  EXPECT_NEAR(s.vertices_per_second, 5e7, 1.0);  // 100 k vertices in 2 ms
  EXPECT_FALSE(s.idle);
}

TEST(TimingOverlay, AnEvaluationStaysReadableWhileResultsAreCached) {
  ui::TimingOverlay overlay;
  overlay.add_frame(sample(10.0, 30, 16, 12, 5, 1, 240000));  // a placement: one evaluation
  for (int i = 1; i <= 120; ++i) overlay.add_frame(sample(10.0 + i / 60.0, 8, 16.7, 0.01, 5, 1, 0));  // cached
  auto s = overlay.summary();
  EXPECT_FALSE(s.ffd_recent);
  EXPECT_DOUBLE_EQ(s.ffd_ms, 12.0);
  EXPECT_DOUBLE_EQ(s.ffd_vertices, 240000.0);
  EXPECT_NEAR(s.vertices_per_second, 2e7, 1e-3);
  EXPECT_NEAR(s.draw_ms, 5.0, 1e-12);
  overlay.add_frame(sample(12.1, 30, 16, 4, 5, 1, 240000));  // a new evaluation
  s = overlay.summary();
  EXPECT_TRUE(s.ffd_recent);
  EXPECT_DOUBLE_EQ(s.ffd_ms, 4.0);
  // The vertex-shader path evaluates while drawing: its throughput is measured against the render pass.
  ui::TimingOverlay vertex;
  ui::FrameSample f = sample(1.0, 9, 16.7, 0.02, 8, 1, 400000);
  f.passes.ffd_in_draw = true;
  vertex.add_frame(f);
  EXPECT_TRUE(vertex.summary().ffd_in_draw);
  EXPECT_NEAR(vertex.summary().vertices_per_second, 5e7, 1e-3);
}

TEST(TimingOverlay, UnmeasuredPassesStayUnknownAndOldFramesLeaveTheGraph) {
  ui::TimingOverlay overlay;
  for (int i = 0; i < 1000; ++i) overlay.add_frame(sample(i * 0.01, 5, 10, -1, -1, -1, 0));  // 10 s at 100 FPS
  EXPECT_LE(overlay.sample_count(), std::size_t(ui::TimingOverlay::kGraphSeconds / 0.01) + 2);
  EXPECT_GE(overlay.sample_count(), std::size_t(ui::TimingOverlay::kGraphSeconds / 0.01) - 2);
  auto s = overlay.summary();
  EXPECT_LT(s.ffd_ms, 0.0);
  EXPECT_LT(s.draw_ms, 0.0);
  EXPECT_LT(s.ui_ms, 0.0);
  EXPECT_LT(s.vertices_per_second, 0.0);
  // The editor sleeps up to 250 ms waiting for input: that is idle, not 4 FPS.
  ui::TimingOverlay idle;
  for (int i = 0; i < 5; ++i) idle.add_frame(sample(i * 0.25, 3, 250, -1, 2, 1, 0));
  EXPECT_TRUE(idle.summary().idle);
}

TEST(TimingOverlay, StageTimingsComeFromCommandStatsInPipelineOrder) {
  const nlohmann::json stats = {
      {"rays_total", 192},
      {"ms", {{"fit", 0.5}, {"rays", 4.0}, {"surface", 1.0}, {"volume", 0.2}, {"embed", 0.1}}},
      {"bvh_ms", 2.0},
      {"evaluate_ms", 3.0},
      {"ms_total", 12.0},
      {"length_axis", "x"},
      {"bad_ms", "not a number"}};
  const auto stages = ui::stage_timings(stats);
  std::vector<std::string> names;
  for (const auto& s : stages) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"bvh", "fit", "rays", "surface", "volume", "embed", "evaluate", "total"}));
  EXPECT_DOUBLE_EQ(stages[2].ms, 4.0);
  EXPECT_TRUE(ui::stage_timings(nlohmann::json::array()).empty());
  EXPECT_TRUE(ui::stage_timings(nlohmann::json()).empty());
  EXPECT_LT(ui::vertices_per_second(0, 1.0), 0.0);
  EXPECT_LT(ui::vertices_per_second(10, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(ui::vertices_per_second(1000, 1.0), 1e6);
}

TEST(TimingOverlay, RealPlacementReportsEveryStage) {
  core::Scene scene;
  editor::History history(scene);
  const auto log = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs" / "place_on_plane.jsonl";
  ASSERT_TRUE(editor::replay_lines(history, log).ok);
  ASSERT_EQ(history.at(history.applied() - 1).id(), "place.sketch");
  const auto stages = ui::stage_timings(history.at(history.applied() - 1).stats());
  std::vector<std::string> names;
  for (const auto& s : stages) {
    names.push_back(s.name);
    EXPECT_GT(s.ms, 0.0) << s.name;
  }
  for (const char* want : {"fit", "rays", "surface", "volume", "embed", "evaluate"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
}

TEST(TimingOverlay, DrawsAWindowInTheViewportCornerOnlyWhenShown) {
  ui::TimingOverlay overlay;
  for (int i = 0; i < 120; ++i) overlay.add_frame(sample(i / 60.0, 9, 16.7, 2, 4, 1, 50000));
  ui::TimingContext ctx;
  ctx.timer_mode = "GPU: glFinish + wall clock (software renderer: llvmpipe timer queries are unreliable)";
  ctx.ffd_backend = "GLSL compute";
  ctx.last_command = "place.sketch";
  ctx.last_command_ms = 40;
  ctx.last_stages = {{"fit", 0.5}, {"rays", 12}};
  overlay.set_context(ctx);
  ui::Rect viewport;
  viewport.pos = ImVec2(300, 20);
  viewport.size = ImVec2(650, 500);

  for (bool shown : {true, false}) {
    ui::ViewToggles view;
    if (!shown) ui::apply_view_action(view, ui::MenuAction::ToggleTimingOverlay);
    HeadlessImGui imgui;
    for (int frame = 0; frame < 2; ++frame) {  // an auto-resized window is measured, hidden, in its first frame
      if (frame) imgui.next_frame();
      if (view.timing_overlay) overlay.draw(viewport);  // as editor/app.cpp does
    }
    ImGuiWindow* w = ImGui::FindWindowByName("##timing_overlay");
    const ImDrawData& dd = imgui.render();
    if (!shown) {
      EXPECT_EQ(w, nullptr);
      EXPECT_EQ(dd.TotalVtxCount, 0);
      continue;
    }
    ASSERT_NE(w, nullptr);
    EXPECT_FLOAT_EQ(w->Pos.x, viewport.pos.x + 10);
    EXPECT_FLOAT_EQ(w->Pos.y, viewport.pos.y + 10);
    EXPECT_GT(w->Size.x, 250.0f) << "graph and text";
    EXPECT_GT(w->Size.y, 150.0f) << "every row";
    EXPECT_LT(w->Pos.x + w->Size.x, viewport.pos.x + viewport.size.x);
    EXPECT_GT(dd.TotalVtxCount, 1000) << "text, graph lines and the background box";
  }
}

TEST(TimingOverlay, TileLineSaysWhatIsDrawn) {
  ui::TimingContext c;
  EXPECT_EQ(ui::ddm_tiles_text(c), "") << "no tile layers: no line";
  c.ddm_instances = 20480;
  c.ddm_drawn = 20480;
  EXPECT_EQ(ui::ddm_tiles_text(c), "tiles 20,480 of 20,480 drawn");
  c.ddm_drawn = 5120;
  c.ddm_culled = 9800;
  c.ddm_keep = 0.25;
  EXPECT_EQ(ui::ddm_tiles_text(c), "tiles 5,120 of 20,480 drawn (moving: 1/4, culled 9,800)");
  c.ddm_keep = 1.0;
  EXPECT_EQ(ui::ddm_tiles_text(c), "tiles 5,120 of 20,480 drawn (culled 9,800)");
}
