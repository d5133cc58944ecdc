// The Incision tool (editor/tools/incision_tool.h) driven like the Press tool tests drive theirs: a drag across a
// sphere previews the cut while dragging (generator curve, cut lattice and cut mesh as gpu::Overlays) and issues
// exactly one incision.draw with the dragged stroke, the panel's values and the view as "camera", undoable bit for
// bit; a click
// issues nothing; a stroke off the surface shows only the stroke and its command error goes to the Log panel with the
// scene unchanged.
#include <gtest/gtest.h>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/incision_tool.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/toolbox.h"
#include "headless_imgui.h"
#include "tool_test.h"
#include "ui/shortcuts.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

using namespace trispline;

namespace {

// The tool's defaults with the cut's width and depth (world units), opening, walls, order and kernel set.
core::IncisionParams incision_params(double width, double depth, double opening, bool walls, int order,
                                     core::IncisionKernel kernel) {
  core::IncisionParams p = editor::incision_tool_defaults();
  p.width = width;
  p.depth = depth;
  p.opening = opening;
  p.walls = walls;
  p.order = order;
  p.kernel = kernel;
  return p;
}

class IncisionTool : public test::ToolTest<editor::IncisionTool> {
 protected:
  // Nothing is selected: the object under the cursor at mouse-down is cut.
  void SetUp() override {
    ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "sphere"}, {"name", "s"}}));
    frame_view_on("s");
    tool.set_preview_interval_ms(0.0);  // a preview after every new stroke point: deterministic
    tool.activate(ctx);
    const std::vector<glm::dvec2> hits = row_hits(0.02);
    ASSERT_GE(hits.size(), 40u) << "the framed sphere must cover part of the middle row";
    row = middle_half(hits);
  }
  const core::SceneObject& object() const { return *s.scene().find("s"); }

  std::vector<glm::dvec2> row;
};

}  // namespace

TEST_F(IncisionTool, LineCarriesStrokeAndParameters) {
  const core::IncisionParams p = incision_params(0.1, 0.07, 0.0, false, 4, core::IncisionKernel::bspline);
  const nlohmann::json j = editor::incision_draw_line("venus", {{10.5, 20}, {30, 40.25}}, p);
  EXPECT_EQ(j["cmd"], "incision.draw");
  EXPECT_EQ(j["object"], "venus");
  EXPECT_EQ(j["stroke"], nlohmann::json::parse("[[10.5,20.0],[30.0,40.25]]"));
  EXPECT_DOUBLE_EQ(j["width"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(j["depth"].get<double>(), 0.07);
  EXPECT_DOUBLE_EQ(j["opening"].get<double>(), 0.0);
  EXPECT_EQ(j["walls"], false);
  EXPECT_EQ(j["order"], 4);
  EXPECT_EQ(j["kernel"], "bspline");
  EXPECT_FALSE(j.contains("camera"));
  core::Camera c;
  c.eye = {1, 2, 3};
  c.viewport = {640, 480};
  const nlohmann::json k = editor::incision_draw_line("venus", {{1, 2}, {3, 4}}, p, c);
  EXPECT_EQ(k["camera"]["eye"], nlohmann::json::parse("[1.0,2.0,3.0]"));
  EXPECT_EQ(k["camera"]["viewport"], nlohmann::json::parse("[640,480]"));
}

TEST_F(IncisionTool, UnsetSizesFollowTheObjectAndExplicitOnesStay) {
  const double diag = core::mesh_bounds(*object().world_mesh).diagonal();
  const core::IncisionParams d = tool.resolved(&object());
  EXPECT_NEAR(d.width, 0.02 * diag, 1e-12);
  EXPECT_NEAR(d.depth, 0.02 * diag, 1e-12);
  EXPECT_NEAR(d.opening, 0.006 * diag, 1e-12);
  core::IncisionParams p = editor::incision_tool_defaults();
  p.width = 0.3;
  p.depth = 0.2;
  p.opening = 0.0;  // zero is a valid opening, not "unset"
  tool.set_params(p);
  const core::IncisionParams r = tool.resolved(&object());
  EXPECT_EQ(r.width, 0.3);
  EXPECT_EQ(r.depth, 0.2);
  EXPECT_EQ(r.opening, 0.0);
}

TEST_F(IncisionTool, PreviewWhileDraggingOnTheSurface) {
  press(row.front());
  move_through({row.begin() + 1, row.end()});
  EXPECT_TRUE(tool.owns_mouse()) << "mid-drag the camera is left alone";
  EXPECT_EQ(tool.target(), "s") << "the object under the cursor at mouse-down";
  ASSERT_FALSE(tool.preview_curve().empty()) << tool.preview_error();
  ASSERT_TRUE(tool.preview_mesh()) << tool.preview_error();
  // G(v) is fitted to the stroke's hits on the unit sphere: every sample lies close to it.
  for (const glm::dvec3& p : tool.preview_curve()) EXPECT_NEAR(glm::length(p), 1.0, 0.05);
  EXPECT_GT(tool.preview_mesh()->vertex_count(), object().world_mesh->vertex_count()) << "the cut adds vertices";

  gpu::ViewOptions vo;
  tool.decorate(vo);
  ASSERT_EQ(vo.overlays.strokes.size(), 1u);
  EXPECT_EQ(vo.overlays.strokes[0].px.size(), row.size());
  ASSERT_EQ(vo.overlays.curves.size(), 1u);
  EXPECT_EQ(vo.overlays.curves[0].points, tool.preview_curve());
  ASSERT_EQ(vo.overlays.meshes.size(), 1u);
  EXPECT_EQ(vo.overlays.meshes[0].mesh, tool.preview_mesh());
  EXPECT_EQ(vo.overlays.meshes[0].object, "s");
  // The cut lattice is shown with the preview: order knots at u = 1/2 (the C⁻¹ break), around the curve, marked
  // as a discontinuity between its F⁻ and F⁺ control planes.
  ASSERT_TRUE(tool.preview_lattice());
  ASSERT_EQ(vo.overlays.lattices.size(), 1u);
  EXPECT_EQ(vo.overlays.lattices[0].lattice, tool.preview_lattice());
  const core::KnotVector& ku = tool.preview_lattice()->knots(0);
  EXPECT_EQ(ku.multiplicity(0.5), ku.order());
  ASSERT_EQ(vo.overlays.lattices[0].discontinuities.size(), 1u);
  const core::Discontinuity& cut = vo.overlays.lattices[0].discontinuities[0];
  EXPECT_EQ(cut.axis, 0);
  EXPECT_EQ(cut.u0, 0.5);
  EXPECT_EQ(ku.knots()[std::size_t(cut.plus_plane)], 0.5) << "F⁺ starts at the first knot u = 1/2";
  EXPECT_EQ(cut.minus_plane, cut.plus_plane - 1);
  EXPECT_EQ(s.history().applied(), 1u) << "nothing is executed before mouse-up";

  release();
  gpu::ViewOptions after;
  tool.decorate(after);
  EXPECT_TRUE(after.overlays.strokes.empty());
  EXPECT_TRUE(after.overlays.curves.empty());
  EXPECT_TRUE(after.overlays.meshes.empty());
  EXPECT_TRUE(after.overlays.lattices.empty());
}

TEST_F(IncisionTool, DragIssuesOneUndoableIncisionDraw) {
  const core::IncisionParams p = incision_params(0.12, 0.09, 0.03, true, 3, core::IncisionKernel::gaussian);
  tool.set_params(p);
  const std::shared_ptr<const core::TriMesh> before = object().world_mesh;
  const std::vector<glm::dvec3> rest_before = object().rest_mesh->positions;
  const std::size_t applied = s.history().applied();
  drag(row);
  ASSERT_EQ(count("incision.draw"), 1u) << last_message();
  const nlohmann::json j = s.history().at(s.history().applied() - 1).to_json();
  if (j.contains("camera")) {
    // The command keeps the stroke's view: the line is self-contained, nothing else is logged.
    ASSERT_EQ(s.history().applied(), applied + 1);
    EXPECT_EQ(j["camera"]["eye"], nlohmann::json({view.eye.x, view.eye.y, view.eye.z}));
  } else {
    // The scene had no camera.set: the view at mouse-down is logged first, then the incision (nothing else).
    ASSERT_EQ(s.history().applied(), applied + 2);
    EXPECT_EQ(s.history().at(applied).id(), "camera.set");
    EXPECT_TRUE(s.scene().camera_set);
    EXPECT_EQ(s.scene().camera.eye, view.eye);
    EXPECT_EQ(s.scene().camera.viewport, view.viewport);
  }

  EXPECT_EQ(j["cmd"], "incision.draw");
  EXPECT_EQ(j["object"], "s");
  ASSERT_EQ(j["stroke"].size(), row.size());
  for (std::size_t i = 0; i < row.size(); ++i) {
    EXPECT_DOUBLE_EQ(j["stroke"][i][0].get<double>(), row[i].x);
    EXPECT_DOUBLE_EQ(j["stroke"][i][1].get<double>(), row[i].y);
  }
  EXPECT_DOUBLE_EQ(j["width"].get<double>(), 0.12);
  EXPECT_DOUBLE_EQ(j["depth"].get<double>(), 0.09);
  EXPECT_DOUBLE_EQ(j["opening"].get<double>(), 0.03);
  EXPECT_EQ(j["walls"], true);
  EXPECT_NE(object().world_mesh, before);
  EXPECT_GT(object().world_mesh->vertex_count(), before->vertex_count());

  // A second stroke with the camera unchanged: no second camera.set.
  std::vector<glm::dvec2> lower = row;
  for (glm::dvec2& q : lower) q.y += 40;
  drag(lower);
  EXPECT_EQ(count("camera.set"), j.contains("camera") ? 0u : 1u);
  EXPECT_EQ(count("incision.draw"), 2u) << last_message();

  while (s.history().applied() > applied) ASSERT_TRUE(s.undo());
  EXPECT_EQ(object().rest_mesh->positions, rest_before) << "undo restores the mesh bit for bit";
  EXPECT_EQ(object().world_mesh->vertex_count(), before->vertex_count());
}

TEST_F(IncisionTool, ClickWithoutDragIssuesNothing) {
  const std::size_t applied = s.history().applied(), logged = messages.messages().size();
  press(row[row.size() / 2]);
  release();
  EXPECT_EQ(s.history().applied(), applied);
  EXPECT_EQ(messages.messages().size(), logged) << last_message();
  EXPECT_FALSE(tool.owns_mouse());
}

TEST_F(IncisionTool, StrokeOffTheSurfaceShowsTheStrokeOnlyAndLogsTheError) {
  selected = "s";  // the press misses every object: the selection is the target
  ASSERT_TRUE(s.execute(editor::camera_line(view)));
  const std::shared_ptr<const core::TriMesh> before = object().world_mesh;
  const std::size_t applied = s.history().applied();
  std::vector<glm::dvec2> corner;
  for (double x = 4; x <= 120; x += 4) corner.push_back({x, 6});
  press(corner.front());
  move_through({corner.begin() + 1, corner.end()});
  EXPECT_EQ(tool.target(), "s");
  EXPECT_TRUE(tool.preview_curve().empty());
  EXPECT_FALSE(tool.preview_mesh());
  EXPECT_FALSE(tool.preview_error().empty());
  gpu::ViewOptions vo;
  tool.decorate(vo);
  ASSERT_EQ(vo.overlays.strokes.size(), 1u) << "the stroke is still shown";
  EXPECT_EQ(vo.overlays.strokes[0].px.size(), corner.size());
  EXPECT_TRUE(vo.overlays.meshes.empty());
  release();
  EXPECT_EQ(s.history().applied(), applied) << "the failing command leaves the history as it was";
  EXPECT_EQ(object().world_mesh, before) << "and the scene";
  EXPECT_TRUE(logged_error("incision.draw")) << last_message();
}

TEST_F(IncisionTool, KeyKActivatesTheIncisionTool) {
  editor::Toolbox box(ctx);
  ASSERT_TRUE(box.activate_shortcut("K"));
  EXPECT_EQ(box.active(), editor::Toolbox::kIncision);
  EXPECT_EQ(box.tool().entry().name, "Incision");
  EXPECT_FALSE(box.activate_shortcut("J")) << "no tool has J";
  EXPECT_EQ(box.active(), editor::Toolbox::kIncision);
  // The key press reaches the toolbox as "K"; letters with modifiers or bound to a menu action (Q, W, E) do not.
  EXPECT_EQ(ui::tool_key({GLFW_KEY_K, 0}), "K");
  EXPECT_EQ(ui::tool_key({GLFW_KEY_K, GLFW_MOD_CONTROL}), "");
  EXPECT_EQ(ui::tool_key({GLFW_KEY_Q, 0}), "");
  EXPECT_EQ(ui::tool_key({GLFW_KEY_F7, 0}), "");
}

TEST_F(IncisionTool, PanelDrawsAndKeepsExplicitValues) {
  selected = "s";
  core::IncisionParams p = editor::incision_tool_defaults();
  p.width = 0.25;
  p.opening = 0.0;
  tool.set_params(p);
  test::HeadlessImGui gui;
  gui.show_window("Tool", [&] { tool.draw_panel(ctx); });
  EXPECT_GT(gui.render().TotalVtxCount, 0);
  EXPECT_EQ(tool.params().width, 0.25) << "drawing does not change the values";
  EXPECT_EQ(tool.params().opening, 0.0);
  EXPECT_LE(tool.params().depth, 0.0) << "an unset depth stays unset (shown resolved)";
}

TEST_F(IncisionTool, StrokeStartingBesideTheObjectCutsTheFirstObjectItCrosses) {
  ASSERT_FALSE(editor::pick_object(s.scene(), view, {4, 300})) << "the stroke starts off the sphere";
  std::vector<glm::dvec2> stroke = {{4, 300}};
  stroke.insert(stroke.end(), row.begin(), row.end());
  press(stroke.front());
  EXPECT_EQ(tool.target(), "") << "nothing under the cursor, nothing selected";
  move_through({stroke.begin() + 1, stroke.end()});
  EXPECT_EQ(tool.target(), "s");
  EXPECT_TRUE(tool.preview_mesh()) << tool.preview_error();
  release();
  ASSERT_EQ(count("incision.draw"), 1u) << last_message();
  EXPECT_EQ(s.history().at(s.history().applied() - 1).to_json()["stroke"].size(), stroke.size());
}
