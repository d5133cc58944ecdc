// The Tile Paint tool (editor/tools/ddm_paint_tool.h) driven through headless ImGui frames: a drag
// over a sphere issues exactly one ddm.paint (the dragged stroke, the view as "camera", the new layer's fields) and
// undo removes what it made; a stroke on an existing layer adds to it and undo restores the instance set exactly;
// Ctrl-drag erases; the brush circle is drawn and [ / ] resize it; Fill and Bake in the panel issue ddm.fill /
// ddm.bake; a stroke off the object logs the error and changes nothing; T activates the tool. And the shipped log
// tests/logs/ddm_paint_teapot.jsonl replayed headless: only cells facing its camera are painted, the erase dab
// removes, the bake holds the layer.
#include <gtest/gtest.h>

#include <filesystem>

#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/ddm_paint_tool.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/toolbox.h"
#include "headless_imgui.h"
#include "tool_test.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

using namespace trispline;

namespace {

class DdmPaintTool : public test::ToolTest<editor::DdmPaintTool> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "sphere"}, {"name", "s"}}));
    frame_view_on("s");
    selected = "s";
    editor::DdmPaintToolParams p;
    p.paint.layer = "spots";
    p.paint.spec.tiles = {"hex"};
    p.paint.spec.counts = {1, 1};
    p.paint.spec.height = 0.03;
    p.paint.spec.base = core::DdmBaseKind::limit;  // a cell per limit chart: three per triangle
    p.paint.radius_px = 30;
    tool.set_params(p);
    tool.activate(ctx);
    const std::vector<glm::dvec2> hits = row_hits(0.05);
    ASSERT_GE(hits.size(), 40u) << "the framed sphere must cover part of the middle row";
    row = middle_half(hits);
  }
  const core::SceneObject& object() const { return *s.scene().find("s"); }
  std::shared_ptr<const core::DdmLayer> layer(const std::string& name = "spots") const {
    for (const auto& l : object().ddm_layers)
      if (l->name == name) return l;
    return nullptr;
  }

  // One frame with the mouse at `px` (viewport pixels = ImGui pixels here), the tool fed as the app does.
  void frame(glm::dvec2 px, bool down) {
    gui.step(ImVec2(float(px.x), float(px.y)), down, [&] {
      const ImGuiIO& io = ImGui::GetIO();
      in.mouse_px = px;
      in.left_pressed = io.MouseClicked[0];
      in.left_down = io.MouseDown[0];
      in.left_released = io.MouseReleased[0];
      tool.handle_input(in, ctx);
    });
  }
  void drag(const std::vector<glm::dvec2>& px, bool ctrl = false) {
    in.ctrl = ctrl;
    frame(px.front(), false);  // hover
    for (const glm::dvec2& p : px) frame(p, true);
    frame(px.back(), false);  // release
    in.ctrl = false;
  }
  void panel_frame(ImVec2 mouse, bool down) {
    gui.step(mouse, down, [&] {
      ImGui::SetNextWindowPos(ImVec2(0, 0));
      ImGui::SetNextWindowSize(ImVec2(420, 700));
      ImGui::Begin("Tool");
      tool.draw_panel(ctx);
      ImGui::End();
    });
  }
  void click(glm::vec4 rect) {
    const ImVec2 c(0.5f * (rect.x + rect.z), 0.5f * (rect.y + rect.w));
    panel_frame(c, false);
    panel_frame(c, true);
    panel_frame(c, false);
  }
  nlohmann::json last_line() const { return s.history().at(s.history().applied() - 1).to_json(); }

  test::HeadlessImGui gui;
  std::vector<glm::dvec2> row;
};

}  // namespace

TEST_F(DdmPaintTool, LinesCarryTheFieldsOfTheCommands) {
  editor::DdmPaintToolParams p;
  p.paint.layer = "thorns";
  p.paint.spec.tiles = {"chain"};
  p.paint.spec.layout = core::DdmLayout::brick;
  p.paint.spec.counts = {3, 2};
  p.paint.spec.height = 0.05;
  p.paint.spec.base = core::DdmBaseKind::teapot_body;
  p.paint.radius_px = 12.5;
  const nlohmann::json a = editor::ddm_paint_line("pot", {{10.5, 20}, {30, 40.25}}, p, true, false);
  EXPECT_EQ(a, nlohmann::json::parse(R"({"cmd":"ddm.paint","object":"pot","layer":"thorns",
      "stroke":[[10.5,20.0],[30.0,40.25]],"radius_px":12.5,"erase":true})"));
  core::Camera c;
  c.viewport = {640, 480};
  const nlohmann::json b = editor::ddm_paint_line("pot", {{1, 2}}, p, false, true, c);
  EXPECT_EQ(b["tile"], "chain");
  EXPECT_EQ(b["layout"], "brick");
  EXPECT_EQ(b["counts"], nlohmann::json::parse("[3,2]"));
  EXPECT_EQ(b["height"], 0.05);
  EXPECT_EQ(b["base"], "teapot_body");
  EXPECT_EQ(b["camera"]["viewport"], nlohmann::json::parse("[640,480]"));
  const nlohmann::json f = editor::ddm_fill_line("pot", p);
  EXPECT_EQ(f, nlohmann::json::parse(R"({"cmd":"ddm.fill","object":"pot","layer":"thorns","tile":"chain",
      "layout":"brick","counts":[3,2],"height":0.05,"base":"teapot_body"})"));
  p.own_color = true;  // "Own colour": the new layer's lines carry it
  p.color = {0.25f, 0.5f, 1.0f};
  EXPECT_EQ(editor::ddm_fill_line("pot", p)["color"], nlohmann::json::parse("[0.25,0.5,1.0]"));
  EXPECT_EQ(editor::ddm_paint_line("pot", {{1, 2}}, p, false, true)["color"], nlohmann::json::parse("[0.25,0.5,1.0]"));
  EXPECT_FALSE(editor::ddm_paint_line("pot", {{1, 2}}, p, false, false).contains("color"));
}

TEST_F(DdmPaintTool, DragIssuesOneUndoableDdmPaint) {
  const std::size_t applied = s.history().applied();
  EXPECT_TRUE(tool.new_layer(ctx));
  drag(row);
  EXPECT_FALSE(tool.owns_mouse());
  ASSERT_EQ(s.history().applied(), applied + 1) << last_message();
  const nlohmann::json j = last_line();
  EXPECT_EQ(j["cmd"], "ddm.paint");
  EXPECT_EQ(j["object"], "s");
  EXPECT_EQ(j["layer"], "spots");
  EXPECT_EQ(j["erase"], false);
  EXPECT_EQ(j["radius_px"], 30.0);
  EXPECT_EQ(j["tile"], "hex") << "the first stroke makes the layer with the panel's settings";
  EXPECT_EQ(j["camera"]["eye"], nlohmann::json({view.eye.x, view.eye.y, view.eye.z}));
  ASSERT_EQ(j["stroke"].size(), row.size());
  EXPECT_EQ(j["stroke"][0][0].get<double>(), row[0].x);
  ASSERT_TRUE(layer());
  EXPECT_FALSE(tool.new_layer(ctx));
  const std::vector<core::DdmInstance> first = layer()->instances;
  EXPECT_GT(first.size(), 5u);
  EXPECT_EQ(s.history().at(applied).stats()["cells_added"], first.size());

  // A second, lower stroke adds to the layer (no layer fields in its line); undo restores the instance set exactly.
  std::vector<glm::dvec2> lower = row;
  for (glm::dvec2& q : lower) q.y += 50;
  drag(lower);
  ASSERT_EQ(count("ddm.paint"), 2u) << last_message();
  EXPECT_FALSE(last_line().contains("tile"));
  EXPECT_GT(layer()->instances.size(), first.size());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(layer()->instances, first);
  ASSERT_TRUE(s.undo());
  EXPECT_FALSE(layer()) << "undo of the first stroke removes the layer it made";
  EXPECT_EQ(s.history().applied(), applied);
}

TEST_F(DdmPaintTool, CtrlDragErasesAndTheToggleInvertsIt) {
  drag(row);
  ASSERT_TRUE(layer()) << last_message();
  const std::size_t painted = layer()->instances.size();
  drag(row, /*ctrl=*/true);
  ASSERT_EQ(count("ddm.paint"), 2u) << last_message();
  EXPECT_EQ(last_line()["erase"], true);
  EXPECT_TRUE(layer()->instances.empty()) << "the same stroke erases every cell it painted";
  EXPECT_EQ(s.history().at(s.history().applied() - 1).stats()["cells_removed"], painted);

  editor::DdmPaintToolParams p = tool.params();
  p.paint.erase = true;
  tool.set_params(p);
  drag(row, /*ctrl=*/true);  // Erase on, Ctrl held: paints
  EXPECT_EQ(last_line()["erase"], false);
  EXPECT_EQ(layer()->instances.size(), painted);
}

TEST_F(DdmPaintTool, BrushCircleFollowsTheCursorAndBracketsResizeIt) {
  frame({400, 300}, false);
  ASSERT_TRUE(tool.hover());
  EXPECT_EQ(*tool.hover(), glm::dvec2(400, 300));
  EXPECT_GT(gui.render().TotalVtxCount, 0) << "the circle is in the background draw list";
  gui.next_frame();
  ImGui::GetIO().KeysDown[GLFW_KEY_RIGHT_BRACKET] = true;
  frame({400, 300}, false);
  ImGui::GetIO().KeysDown[GLFW_KEY_RIGHT_BRACKET] = false;
  EXPECT_NEAR(tool.params().paint.radius_px, 30 * 1.15, 1e-9);
  frame({400, 300}, false);
  ImGui::GetIO().KeysDown[GLFW_KEY_LEFT_BRACKET] = true;
  frame({400, 300}, false);
  ImGui::GetIO().KeysDown[GLFW_KEY_LEFT_BRACKET] = false;
  EXPECT_NEAR(tool.params().paint.radius_px, 30.0, 1e-9);
  tool.scale_radius(1e6);
  EXPECT_EQ(tool.params().paint.radius_px, editor::DdmPaintTool::kMaxRadiusPx);
  tool.mouse_away();
  EXPECT_FALSE(tool.hover());

  // While dragging the view shows the stroke; nothing is executed before mouse-up.
  in.ctrl = false;
  frame(row.front(), true);
  frame(row.back(), true);
  EXPECT_TRUE(tool.owns_mouse());
  gpu::ViewOptions vo;
  tool.decorate(vo);
  ASSERT_EQ(vo.overlays.strokes.size(), 1u);
  EXPECT_EQ(vo.overlays.strokes[0].px.size(), 2u);
  EXPECT_EQ(count("ddm.paint"), 0u);
  frame(row.back(), false);
  EXPECT_EQ(count("ddm.paint"), 1u) << last_message();
}

TEST_F(DdmPaintTool, FillAndBakeButtons) {
  for (int f = 0; f < 2; ++f) panel_frame({-10, -10}, false);  // a new window is hidden in its first frame
  EXPECT_GT(tool.fill_button().z, tool.fill_button().x) << "the Fill button is drawn";
  click(tool.fill_button());
  ASSERT_EQ(count("ddm.fill"), 1u) << last_message();
  EXPECT_EQ(last_line()["tile"], "hex");
  ASSERT_TRUE(layer());
  EXPECT_EQ(layer()->instances.size(), 3 * object().rest_mesh->triangle_count()) << "one cell per chart";
  panel_frame({-10, -10}, false);
  click(tool.bake_button());
  ASSERT_EQ(count("ddm.bake"), 1u) << last_message();
  const core::SceneObject* baked = s.scene().find("s.spots");
  ASSERT_TRUE(baked);
  EXPECT_EQ(baked->rest_mesh->vertex_count(), layer()->mesh->vertex_count());
  // The Layer colour swatch and its "Object's" button each issue one ddm.color.
  tool.set_layer_color(ctx, glm::vec3(0.2f, 0.4f, 0.6f));
  ASSERT_EQ(count("ddm.color"), 1u) << last_message();
  EXPECT_EQ(*layer()->color, glm::vec3(0.2f, 0.4f, 0.6f));
  tool.set_layer_color(ctx, std::nullopt);
  EXPECT_EQ(count("ddm.color"), 2u);
  EXPECT_FALSE(layer()->color.has_value());
  // Remove deletes the layer (one ddm.remove); undo brings it back, the same layer object.
  const auto held = object().ddm_layers.at(0);
  panel_frame({-10, -10}, false);
  click(tool.remove_button());
  ASSERT_EQ(count("ddm.remove"), 1u) << last_message();
  EXPECT_TRUE(object().ddm_layers.empty());
  ASSERT_TRUE(s.undo());
  ASSERT_EQ(object().ddm_layers.size(), 1u);
  EXPECT_EQ(object().ddm_layers[0], held);
}

TEST_F(DdmPaintTool, SelectingAnObjectWithLayersBringsUpItsLastLayer) {
  ASSERT_TRUE(s.execute({{"cmd", "scene.primitive"}, {"kind", "sphere"}, {"name", "t"}, {"translate", {3, 0, 0}}}));
  ASSERT_TRUE(
      s.execute(nlohmann::json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"t","layer":"dots","tile":"hex",
      "layout":"rect","counts":[1,1],"height":0.02})")));
  EXPECT_EQ(tool.params().paint.layer, "spots");  // "s" has no layers: the panel keeps the new layer's name
  selected = "t";
  panel_frame({-10, -10}, false);
  EXPECT_EQ(tool.params().paint.layer, "dots");
  selected = "s";  // back to an object without layers: the name stays (the next stroke makes "dots" there)
  panel_frame({-10, -10}, false);
  EXPECT_EQ(tool.params().paint.layer, "dots");
}

TEST_F(DdmPaintTool, StrokeOffTheObjectLogsTheErrorAndChangesNothing) {
  const std::size_t applied = s.history().applied();
  drag({{4, 6}, {60, 8}});
  EXPECT_EQ(s.history().applied(), applied);
  EXPECT_FALSE(layer());
  EXPECT_NE(last_message().find("touches no visible cell"), std::string::npos) << last_message();
}

TEST_F(DdmPaintTool, KeyTActivatesTilePaint) {
  editor::Toolbox box(ctx);
  ASSERT_TRUE(box.activate_shortcut("T"));
  EXPECT_EQ(box.active(), editor::Toolbox::kDdmPaint);
  EXPECT_EQ(box.tool().entry().name, "Tile Paint");
  EXPECT_FALSE(box.tool().entry().tooltip.empty());
}

TEST(DdmPaintLog, TeapotLogPaintsTheFrontOnlyErasesAndBakes) {
  core::Scene scene;
  editor::History history(scene);
  const auto r = editor::replay_lines(
      history, std::filesystem::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs" / "ddm_paint_teapot.jsonl");
  ASSERT_TRUE(r.ok) << r.error;
  std::vector<nlohmann::json> paints;
  for (const auto& rec : r.records)
    if (rec.cmd == "ddm.paint") paints.push_back(rec.stats);
  ASSERT_EQ(paints.size(), 4u);
  EXPECT_EQ(paints[0]["created"], true);
  EXPECT_GT(paints[0]["cells_added"].get<int>(), 5);
  EXPECT_GT(paints[1]["cells_added"].get<int>(), 5);
  EXPECT_EQ(paints[2]["cells_added"], 0);
  EXPECT_GE(paints[2]["cells_removed"].get<int>(), 1) << "the erase dab";
  EXPECT_EQ(paints[2]["tiles"].get<int>(), paints[1]["tiles"].get<int>() - paints[2]["cells_removed"].get<int>());
  for (const char* name : {"pot", "ball"}) {
    const core::SceneObject& o = *scene.find(name);
    ASSERT_EQ(o.ddm_layers.size(), 1u) << name;
    const core::DdmLayer& layer = *o.ddm_layers[0];
    ASSERT_FALSE(layer.instances.empty()) << name;
    const glm::dmat4 m = o.transform.matrix();
    const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(m)));
    for (const core::DdmInstance& c : layer.instances) {
      const glm::dvec2 uv = c.origin + 0.5 * c.size;
      const core::DdmSurfacePoint sp = layer.surface->eval(c.chart, uv.x, uv.y);
      const glm::dvec3 p = glm::dvec3(m * glm::dvec4(sp.p, 1.0));
      EXPECT_GT(glm::dot(nm * sp.n, scene.camera.eye - p), 0.0) << name << " chart " << c.chart << " faces away";
    }
  }
  const core::SceneObject* baked = scene.find("pot.thorns");
  ASSERT_TRUE(baked);
  EXPECT_EQ(baked->rest_mesh->vertex_count(), scene.find("pot")->ddm_layers[0]->mesh->vertex_count());
}
