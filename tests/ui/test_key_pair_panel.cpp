// The two-key panel (ui/key_pair_panel.h) behind the Incision tool's "Opening over time" and the Split tool's "Seam
// over time": its keys, its reasons for a disabled Animate, and one headless frame that names its widgets and
// reports no click.
#include <gtest/gtest.h>

#include "headless_imgui.h"
#include "ui/gui_probe.h"
#include "ui/key_pair_panel.h"

using namespace trispline;

namespace {

TEST(KeyPairPanel, KeysAndBlockedReasons) {
  ui::KeyPairParams p{3, 30, 0.25, 2.0, "linear"};
  const std::vector<glm::dvec2> keys = ui::key_pair_keys(p);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0], glm::dvec2(3.0, 0.25));
  EXPECT_EQ(keys[1], glm::dvec2(30.0, 2.0));
  EXPECT_EQ(ui::key_pair_blocked(p, ""), "");
  EXPECT_EQ(ui::key_pair_blocked(p, "select an object"), "select an object");  // the tool's reason comes first
  p.frame_to = p.frame_from;
  EXPECT_NE(ui::key_pair_blocked(p, "").find("frame from < frame to"), std::string::npos);
}

TEST(KeyPairPanel, AHeadlessFrameNamesItsWidgets) {
  ui::KeyPairParams p;
  const ui::KeyPairSpec spec{"seam", "Stitch", "0 capped, 1 stitched", "Key it", "Remove the keys"};
  ui::probe::set_enabled(true);
  ui::probe::begin_frame();
  test::HeadlessImGui gui;
  gui.step({-10, -10}, false, [&] {
    ImGui::Begin("Tool");
    const ui::KeyPairResult r = ui::draw_key_pair_panel(p, spec, "", false);
    EXPECT_FALSE(r.animate);
    EXPECT_FALSE(r.clear);
    ImGui::End();
  });
  for (const char* name :
       {"seam.frame_from", "seam.frame_to", "seam.value_from", "seam.value_to", "seam.animate", "seam.clear"})
    EXPECT_EQ(ui::probe::items().count(name), 1u) << name;
  ui::probe::set_enabled(false);
}

}  // namespace
