// The Press tool (editor/tools/press_tool.h) driven like the Sketch placement tests drive theirs: hovering puts the
// brush sphere on the object's deformed mesh, a drag issues exactly one lattice.press (undoable), a drag that never
// touches the object issues nothing, Ctrl-drag pulls.
#include <gtest/gtest.h>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/press_tool.h"
#include "editor/tools/select_tool.h"
#include "tool_test.h"

using namespace trispline;

namespace {

class PressTool : public test::ToolTest<editor::PressTool> {
 protected:
  void SetUp() override {
    selected = "t";
    ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}}));
    ASSERT_TRUE(s.execute(
        {{"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}}));
    frame_view_on("t");
    tool.activate(ctx);
    row = row_hits();  // a row through the middle of the view: the pixels whose rays hit the teapot
    ASSERT_GE(row.size(), 20u) << "the framed teapot must cover part of the middle row";
  }
  const core::SceneObject& object() const { return *s.scene().find("t"); }
  double diagonal() const { return core::mesh_bounds(*object().world_mesh).diagonal(); }

  void hover(glm::dvec2 px) {
    editor::ToolInput moved;
    moved.mouse_px = px;
    tool.handle_input(moved, ctx);
  }

  std::vector<glm::dvec2> row;
};

}  // namespace

TEST_F(PressTool, HoverPutsTheBrushSphereOnTheDeformedMesh) {
  const glm::dvec2 px = row[row.size() / 2];
  hover(px);
  ASSERT_TRUE(tool.hover());
  gpu::ViewOptions vo;
  tool.decorate(vo);
  ASSERT_EQ(vo.overlays.spheres.size(), 1u);
  const gpu::SphereOverlay& brush = vo.overlays.spheres[0];
  EXPECT_NEAR(brush.radius, 0.1 * diagonal(), 1e-12) << "unset radius: 0.1 x the bounding-box diagonal";
  // The centre is the first hit on the object's world_mesh along the cursor's ray.
  core::RayCaster caster;
  caster.add_mesh(*object().world_mesh);
  caster.commit();
  const auto hit = caster.intersect(view.eye, view.ray_direction(px));
  ASSERT_TRUE(hit);
  EXPECT_LT(glm::length(brush.centre - hit->position), 1e-9 * diagonal());
  EXPECT_TRUE(vo.overlays.points.empty()) << "no path while only hovering";

  hover({2, 2});  // off the object: no sphere
  EXPECT_FALSE(tool.hover());
  gpu::ViewOptions off;
  tool.decorate(off);
  EXPECT_TRUE(off.overlays.spheres.empty());

  hover(px);
  tool.mouse_away();  // over a panel
  EXPECT_FALSE(tool.hover());
}

TEST_F(PressTool, DragIssuesOneUndoablePress) {
  const double radius = 0.3 * diagonal();  // before the press changes the mesh
  tool.set_radius(radius);
  tool.set_falloff(core::Falloff::hat);
  const auto before = object().ffd->lattice.control_points();
  const std::size_t applied = s.history().applied();
  drag(row);
  ASSERT_EQ(s.history().applied(), applied + 1) << last_message();
  const nlohmann::json j = s.history().at(applied).to_json();
  EXPECT_EQ(j["cmd"], "lattice.press");
  EXPECT_EQ(j["object"], "t");
  EXPECT_GE(j["path"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["radius"].get<double>(), radius);
  EXPECT_DOUBLE_EQ(j["strength"].get<double>(), 0.25 * radius) << "default strength: a quarter of the radius";
  EXPECT_EQ(j["falloff"], "hat");
  // Consecutive samples are at least radius/4 apart.
  for (std::size_t i = 1; i < j["path"].size(); ++i) {
    const auto& a = j["path"][i - 1];
    const auto& b = j["path"][i];
    const glm::dvec3 d(b[0].get<double>() - a[0].get<double>(), b[1].get<double>() - a[1].get<double>(),
                       b[2].get<double>() - a[2].get<double>());
    EXPECT_GE(glm::length(d), 0.25 * radius - 1e-12);
  }
  EXPECT_NE(object().ffd->lattice.control_points(), before) << "the press must move control points";
  EXPECT_TRUE(tool.path().empty());

  ASSERT_TRUE(s.undo());
  EXPECT_EQ(object().ffd->lattice.control_points(), before) << "undo restores the lattice";
}

// The drag preview (live_preview) shows, while the button is down, exactly the lattice the command at mouse-up
// produces, and goes away once the command has replaced the object's lattice.
TEST_F(PressTool, LivePreviewDuringTheDragEqualsTheCommittedPress) {
  EXPECT_FALSE(tool.live_preview(ctx));  // nothing before a drag
  press(row[row.size() / 3]);
  move_through({row.begin() + std::ptrdiff_t(row.size() / 3 + 1), row.begin() + std::ptrdiff_t(2 * row.size() / 3)});
  const auto before = object().ffd;
  const auto preview = tool.live_preview(ctx);
  ASSERT_TRUE(preview);
  EXPECT_EQ(preview->object, "t");
  EXPECT_NE(preview->lattice->control_points(), before->lattice.control_points());  // it pressed
  EXPECT_EQ(preview->lattice->control_counts(), before->lattice.control_counts());
  EXPECT_EQ(object().ffd, before);  // the scene is untouched until mouse-up
  release();                        // commits (this test's defer runs the work at once)
  ASSERT_NE(object().ffd, before);
  EXPECT_EQ(object().ffd->lattice.control_points(), preview->lattice->control_points());
  EXPECT_FALSE(tool.live_preview(ctx));  // the object's own lattice is shown again
}

TEST_F(PressTool, DragThatNeverHitsTheObjectIssuesNothing) {
  const std::size_t applied = s.history().applied();
  std::vector<glm::dvec2> top;
  for (double x = 10; x < 790; x += 20) top.push_back({x, 2});
  drag(top);
  EXPECT_EQ(s.history().applied(), applied);
  EXPECT_EQ(s.history().size(), applied);
}

TEST_F(PressTool, CtrlDragPullsWithNegativeStrength) {
  tool.set_radius(0.3 * diagonal());
  tool.set_strength(0.02);
  const std::size_t applied = s.history().applied();
  drag(row, /*ctrl=*/true);
  ASSERT_EQ(s.history().applied(), applied + 1) << last_message();
  EXPECT_DOUBLE_EQ(s.history().at(applied).to_json()["strength"].get<double>(), -0.02);
  EXPECT_EQ(s.history().at(applied).label().rfind("Pull '", 0), 0u) << s.history().at(applied).label();
}

TEST_F(PressTool, ObjectWithoutLatticeShowsNoBrush) {
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "b"}}));
  tool.set_object("b");
  hover(row[row.size() / 2]);
  EXPECT_FALSE(tool.hover());
  EXPECT_DOUBLE_EQ(tool.radius(ctx), 0.0);
}
