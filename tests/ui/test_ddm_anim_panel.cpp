// The tile animation panel (ui/ddm_anim_panel.h; seed §5.4.2, Eq. 5.3): the ddm.animate lines it builds apply to a
// real layer (metamorphosis keys over the chosen frames, offset speed, clear), its reasons for a disabled Animate
// button, and one headless frame of the panel that keeps a valid layer selected.
#include <gtest/gtest.h>

#include "core/commands/ddm_animate.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/scene_primitive.h"
#include "headless_imgui.h"
#include "ui/ddm_anim_panel.h"

using namespace trispline;
using nlohmann::json;

namespace {

core::Scene pot() {
  core::Scene s;
  core::ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})
      ->redo(s);
  core::DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","object":"pot","layer":"t","tile":"thorn",
      "layout":"rect","counts":[8,2],"height":0.05,"base":"teapot_body","map_resolution":[33,17]})"),
                              {})
      ->redo(s);
  return s;
}

TEST(DdmAnimPanel, LinesApplyToTheLayer) {
  core::Scene s = pot();
  ui::DdmAnimParams p;
  p.frame_from = 1, p.frame_to = 25, p.speed_u = 0.25;
  EXPECT_EQ(ui::ddm_animate_blocked("pot", "t", p), "");
  const json line = ui::ddm_animate_line("pot", "t", p);
  EXPECT_EQ(line["alpha_keys"], json::parse("[[1,0.0],[25,1.0]]"));
  core::DdmAnimateCommand::parse(line, {})->redo(s);
  const core::DdmLayer& l = *s.find("pot")->ddm_layers.at(0);
  EXPECT_DOUBLE_EQ(l.alpha_at(0.5), 0.5);  // frame 13 at 24 fps, eased: the middle is the middle
  EXPECT_DOUBLE_EQ(l.offset_at(2.0).x, 0.5);
  // Offset only: the morph is removed with α back to 0.
  ui::DdmAnimParams offset_only = p;
  offset_only.morph_tile.clear();
  core::DdmAnimateCommand::parse(ui::ddm_animate_line("pot", "t", offset_only), {})->redo(s);
  EXPECT_TRUE(s.find("pot")->ddm_layers.at(0)->morph_tiles.empty());
  EXPECT_TRUE(s.find("pot")->ddm_layers.at(0)->animated());
  core::DdmAnimateCommand::parse(ui::ddm_animate_line("pot", "t", p, true), {})->redo(s);
  EXPECT_FALSE(s.find("pot")->ddm_layers.at(0)->animated());
}

// Turn, scale and w over the panel's frames (seed §5.4.2): keys only for the values moved from rest, and a second
// Animate with them back at rest removes those keys.
TEST(DdmAnimPanel, TurnScaleAndWLinesKeyTheLayer) {
  core::Scene s = pot();
  ui::DdmAnimParams p;
  p.morph_tile.clear();
  p.frame_from = 1, p.frame_to = 25, p.interpolation = "linear";
  EXPECT_NE(ui::ddm_animate_blocked("pot", "t", p).find("nothing to animate"), std::string::npos);
  p.turn_to = 360.0, p.w_to = 2.0;
  EXPECT_EQ(ui::ddm_animate_blocked("pot", "t", p), "");
  const json line = ui::ddm_animate_line("pot", "t", p);
  EXPECT_EQ(line["rotate_keys"], json::parse("[[1,0.0],[25,360.0]]"));
  EXPECT_EQ(line["w_keys"], json::parse("[[1,1.0],[25,2.0]]"));
  EXPECT_EQ(line["scale_keys"], json::array());
  core::DdmAnimateCommand::parse(line, {})->redo(s);
  const core::DdmLayer& l = *s.find("pot")->ddm_layers.at(0);
  EXPECT_DOUBLE_EQ(l.transform_at(0.5).rotate_deg, 180.0);
  EXPECT_DOUBLE_EQ(l.height_at(1.0), 0.1);
  EXPECT_TRUE(l.scale_keys.empty());
  p.scale_to = 0.0;
  EXPECT_NE(ui::ddm_animate_blocked("pot", "t", p).find("scale"), std::string::npos);
  p.scale_to = 1.0, p.turn_to = 0.0, p.w_to = 1.0, p.speed_u = 0.1;
  core::DdmAnimateCommand::parse(ui::ddm_animate_line("pot", "t", p), {})->redo(s);
  const core::DdmLayer& after = *s.find("pot")->ddm_layers.at(0);
  EXPECT_TRUE(after.rotate_keys.empty() && after.w_keys.empty());
  EXPECT_TRUE(after.animated());  // the offset speed alone
}

TEST(DdmAnimPanel, BlockedReasonsAndAHeadlessFrame) {
  ui::DdmAnimParams p;
  EXPECT_NE(ui::ddm_animate_blocked("", "t", p), "");
  EXPECT_NE(ui::ddm_animate_blocked("pot", "", p), "");
  p.frame_to = p.frame_from;
  EXPECT_NE(ui::ddm_animate_blocked("pot", "t", p).find("frame"), std::string::npos);
  p.morph_tile.clear();
  EXPECT_NE(ui::ddm_animate_blocked("pot", "t", p).find("nothing to animate"), std::string::npos);
  test::HeadlessImGui gui;
  std::string layer = "gone";
  gui.step({-10, -10}, false, [&] {
    ImGui::Begin("Tool");
    const auto r = ui::draw_ddm_anim_panel(p, layer, "pot", {{"t", "thorn", 16, 10016, false}});
    EXPECT_FALSE(r.line.has_value());
    ImGui::End();
  });
  EXPECT_EQ(layer, "t");  // a layer no longer on the object falls back to the first one
}

}  // namespace
