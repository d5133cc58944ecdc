// The "Split (DFFD)" tool: the dffd.split line its panel builds (ui/dffd_panel.h: fields, automatic kernel width,
// optional margin), the Split button in a headless ImGui frame (disabled, with the reason, when no obstacle is ticked
// or the axes coincide), and the tool executing the line as one undoable dffd.split (editor/tools/dffd_tool.h).
#include <gtest/gtest.h>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/dffd_tool.h"
#include "editor/tools/toolbox.h"
#include "headless_imgui.h"
#include "ui/dffd_panel.h"

using namespace trispline;

namespace {

const std::vector<ui::DffdObstacleInfo> kCandidates = {
    {"bar1", {0.4, 1.8, 0.4}}, {"bar2", {0.6, 1.0, 0.2}}, {"wall", {0.1, 2.0, 3.0}}};

// Draws the panel in a fixed window for one frame with the mouse at `mouse` (button `down`); returns its result.
ui::DffdPanelResult frame(test::HeadlessImGui& gui, ImVec2 mouse, bool down, core::DffdSplitParams& p,
                          const std::string& object) {
  ui::DffdPanelResult r;
  gui.step(mouse, down, [&] {
    ImGui::SetNextWindowPos({0, 0});
    ImGui::SetNextWindowSize({420, 700});
    ImGui::Begin("Tool", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    r = ui::draw_dffd_panel(p, object, kCandidates);
    ImGui::End();
  });
  return r;
}

// Presses and releases the Split button; the line of the frame where it fired, if any.
std::optional<nlohmann::json> click_split(core::DffdSplitParams& p, const std::string& object) {
  test::HeadlessImGui gui;
  const ui::DffdPanelResult first = frame(gui, {-10, -10}, false, p, object);
  EXPECT_GT(first.button_max.x, first.button_min.x) << "the Split button is drawn";
  const ImVec2 c{0.5f * (first.button_min.x + first.button_max.x), 0.5f * (first.button_min.y + first.button_max.y)};
  std::optional<nlohmann::json> line;
  for (bool down : {false, true, false, false})
    if (auto r = frame(gui, c, down, p, object); r.line) line = r.line;
  return line;
}

}  // namespace

TEST(DffdPanel, LineCarriesTheChosenFields) {
  core::DffdSplitParams p;
  p.obstacles = {"bar1", "wall"};
  p.dffd.axis = 2;
  p.dffd.w_axis = 1;
  p.dffd.order[0] = 4;
  p.dffd.controls[0] = 14;
  p.dffd.kernel = core::DffdKernel::bspline;
  p.dffd.kernel_width = 0.55;
  p.dffd.openings = core::DffdOpenings::stitch;
  p.dffd.reject_fold = false;
  const nlohmann::json j = ui::dffd_split_line("bunny", p, kCandidates);
  EXPECT_EQ(j["cmd"], "dffd.split");
  EXPECT_EQ(j["object"], "bunny");
  EXPECT_EQ(j["obstacles"], nlohmann::json::parse(R"(["bar1","wall"])"));
  EXPECT_EQ(j["axis"], "z");
  EXPECT_EQ(j["w_axis"], "y");
  EXPECT_EQ(j["order"], nlohmann::json::parse("[4,3,3]"));
  EXPECT_EQ(j["controls"], nlohmann::json::parse("[14,8,8]"));
  EXPECT_EQ(j["kernel"], "bspline");
  EXPECT_DOUBLE_EQ(j["kernel_width"].get<double>(), 0.55);
  EXPECT_EQ(j["openings"], "stitch");
  EXPECT_EQ(j["fold"], "warn");
  EXPECT_FALSE(j.contains("margin")) << "no margin leaves the command's default";
  p.dffd.margin = 0.25;
  EXPECT_DOUBLE_EQ(ui::dffd_split_line("bunny", p, kCandidates)["margin"].get<double>(), 0.25);
}

TEST(DffdPanel, DefaultsAndAutomaticKernelWidth) {
  core::DffdSplitParams p;
  EXPECT_EQ(p.dffd.order[0], 3);
  EXPECT_EQ(p.dffd.controls[0], 12);
  EXPECT_EQ(p.dffd.controls[1], 8);
  EXPECT_EQ(p.dffd.controls[2], 8);
  EXPECT_EQ(p.dffd.kernel, core::DffdKernel::gaussian);
  EXPECT_EQ(p.dffd.openings, core::DffdOpenings::cap);
  EXPECT_TRUE(p.dffd.reject_fold);
  EXPECT_EQ(ui::default_kernel_width(p, kCandidates), 0.0) << "nothing ticked";
  p.obstacles = {"bar1", "bar2"};
  EXPECT_DOUBLE_EQ(ui::default_kernel_width(p, kCandidates), 2 * 0.6) << "2 x the largest extent along x";
  p.dffd.axis = 2;
  EXPECT_DOUBLE_EQ(ui::default_kernel_width(p, kCandidates), 2 * 0.4);
  EXPECT_DOUBLE_EQ(ui::dffd_split_line("o", p, kCandidates)["kernel_width"].get<double>(), 0.8);
}

TEST(DffdPanel, BlockedReasons) {
  core::DffdSplitParams p;
  EXPECT_NE(ui::dffd_split_blocked("", p), "");
  EXPECT_NE(ui::dffd_split_blocked("o", p).find("obstacle"), std::string::npos);
  p.obstacles = {"bar1"};
  EXPECT_EQ(ui::dffd_split_blocked("o", p), "");
  p.dffd.w_axis = p.dffd.axis;
  EXPECT_NE(ui::dffd_split_blocked("o", p).find("differ"), std::string::npos);
}

TEST(DffdPanel, SplitButtonIssuesTheLine) {
  core::DffdSplitParams p;
  p.obstacles = {"wall", "gone", "bar2"};  // "gone" is no longer a candidate: dropped; scene order kept
  p.dffd.openings = core::DffdOpenings::open;
  const auto line = click_split(p, "bunny");
  ASSERT_TRUE(line) << "a click on the enabled Split button gives the dffd.split line";
  EXPECT_EQ((*line)["obstacles"], nlohmann::json::parse(R"(["bar2","wall"])"));
  EXPECT_EQ((*line)["openings"], "open");
  EXPECT_DOUBLE_EQ((*line)["kernel_width"].get<double>(), 2 * 0.6);
}

TEST(DffdPanel, DisabledButtonIssuesNothing) {
  core::DffdSplitParams none;
  EXPECT_FALSE(click_split(none, "bunny")) << "no obstacle ticked";
  core::DffdSplitParams same;
  same.obstacles = {"bar1"};
  same.dffd.w_axis = same.dffd.axis;
  EXPECT_FALSE(click_split(same, "bunny")) << "axis = w_axis";
  core::DffdSplitParams self;
  self.obstacles = {"bar1"};
  EXPECT_FALSE(click_split(self, "bar1")) << "the object cannot be its own obstacle";
}

TEST(DffdSplitTool, SplitIsOneUndoableCommand) {
  ui::MessageLog messages;
  editor::EditorSession s{messages};
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "sphere"}, {"name", "ball"}}));
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"},
                         {"kind", "cylinder"},
                         {"name", "bar"},
                         {"translate", {0.05, 0.8, 0.0}},
                         {"scale", {0.2, 0.9, 0.2}}}));
  core::Camera view;
  std::string selected = "ball";
  editor::ToolContext ctx{s, view, selected, [](std::string, std::function<void()> work) { work(); }, nullptr};
  editor::Toolbox box(ctx);
  box.set_active(editor::Toolbox::kDffdSplit);
  auto& tool = dynamic_cast<editor::DffdTool&>(box.tool());

  const auto candidates = tool.candidates(ctx, "ball");
  ASSERT_EQ(candidates.size(), 1u) << "the other visible objects";
  EXPECT_EQ(candidates[0].name, "bar");
  EXPECT_NEAR(candidates[0].extent.x, 0.4, 1e-9);
  ASSERT_TRUE(s.execute({{"cmd", "object.visibility"}, {"object", "bar"}, {"viewport", false}}));
  EXPECT_TRUE(tool.candidates(ctx, "ball").empty()) << "hidden objects are not offered";
  ASSERT_TRUE(s.undo());

  core::DffdSplitParams& p = tool.params();
  p.obstacles = {"bar"};
  const nlohmann::json line = ui::dffd_split_line("ball", p, candidates);
  EXPECT_DOUBLE_EQ(line["kernel_width"].get<double>(), 0.8);
  const auto before = s.scene().find("ball")->world_mesh;
  const std::size_t applied = s.history().applied();
  tool.split(ctx, line);
  ASSERT_EQ(s.history().applied(), applied + 1) << (messages.messages().empty() ? "" : messages.messages().back().text);
  EXPECT_EQ(s.history().at(applied).id(), "dffd.split");
  EXPECT_EQ(s.history().at(applied).to_json()["obstacles"], nlohmann::json::parse(R"(["bar"])"));
  EXPECT_GT(s.scene().find("ball")->world_mesh->vertex_count(), before->vertex_count()) << "the mesh is split";
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.scene().find("ball")->world_mesh->positions, before->positions) << "undo restores it";

  test::HeadlessImGui gui;  // the tool's panel for the selected object, the obstacle ticked above kept
  gui.show_window("Tool", [&] { tool.draw_panel(ctx); });
  EXPECT_GT(gui.render().TotalVtxCount, 0);
  EXPECT_EQ(tool.params().obstacles, std::vector<std::string>{"bar"});

  gpu::ViewOptions vo;
  vo.show_discontinuities = false;
  box.decorate(vo);
  EXPECT_TRUE(vo.show_discontinuities) << "the Split tool shows the discontinuity planes";
}
