// The Press tool's default radius (0.1 × the bounding-box diagonal of the object's world_mesh) is cached per mesh
// (editor/tools/press_tool.h): it must follow the mesh whenever a command replaces it (press, undo, redo).
#include <gtest/gtest.h>

#include <cmath>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/press_tool.h"

using namespace trispline;

TEST(PressToolRadius, DefaultRadiusFollowsTheWorldMeshThroughPressUndoRedo) {
  ui::MessageLog messages;
  editor::EditorSession s{messages};
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}}));
  ASSERT_TRUE(s.execute(
      {{"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}}));
  core::Camera view;
  std::string selected = "t";
  editor::ToolContext ctx{s, view, selected, [](std::string, std::function<void()> work) { work(); }, nullptr};
  editor::PressTool tool;
  tool.activate(ctx);
  const auto expected = [&] { return 0.1 * core::mesh_bounds(*s.scene().find("t")->world_mesh).diagonal(); };

  const double r0 = expected();
  EXPECT_DOUBLE_EQ(tool.radius(ctx), r0);
  EXPECT_DOUBLE_EQ(tool.radius(ctx), r0) << "asked again (cached)";

  // A press at the top of the bounding box, linear falloff: the top moves more than the bottom, the box changes.
  const core::Aabb box = core::mesh_bounds(*s.scene().find("t")->world_mesh);
  const glm::dvec3 top(0.5 * (box.lo.x + box.hi.x), box.hi.y, 0.5 * (box.lo.z + box.hi.z));
  ASSERT_TRUE(s.execute({{"cmd", "lattice.press"},
                         {"object", "t"},
                         {"path", {{top.x, top.y, top.z}}},
                         {"radius", 5.0 * r0},
                         {"strength", 2.0 * r0},
                         {"falloff", "hat"}}))
      << messages.messages().back().text;
  const double r1 = expected();
  ASSERT_GT(std::abs(r1 - r0), 1e-3 * r0) << "the press must change the bounding box for this test to mean much";
  EXPECT_DOUBLE_EQ(tool.radius(ctx), r1) << "a new world_mesh: the cached diagonal is recomputed";

  ASSERT_TRUE(s.undo());
  EXPECT_DOUBLE_EQ(tool.radius(ctx), r0);
  ASSERT_TRUE(s.redo());
  EXPECT_DOUBLE_EQ(tool.radius(ctx), r1);
  tool.set_radius(0.5);
  EXPECT_DOUBLE_EQ(tool.radius(ctx), 0.5) << "an explicit radius wins";
}
