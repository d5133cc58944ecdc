// ddm.paint (core/commands/ddm_paint.h; seed ch. 5): a stroke over a sphere adds exactly the cells
// whose centres project within the brush radius and face the camera (the back of the sphere, under the same pixels,
// stays bare; cells behind another object too); erase removes them; undo restores the instance set exactly; several
// tiles follow ddm.fill's pattern; a stroke that touches nothing and bad fields are CommandErrors naming the field,
// with the scene unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "core/commands/camera_set.h"
#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_paint.h"
#include "core/commands/ddm_remove.h"
#include "core/params/codecs.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/primitives.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

using nlohmann::json;
using Key = std::tuple<int, double, double, int>;  // chart, origin, tile

Key key(const DdmInstance& c) { return {c.chart, c.origin.x, c.origin.y, c.tile}; }
std::set<Key> keys(const std::vector<DdmInstance>& v) {
  std::set<Key> s;
  for (const DdmInstance& c : v) s.insert(key(c));
  return s;
}

Camera view() {
  Camera c;
  c.eye = {0.3, 0.0, 4.0};
  c.target = {0.3, 0.0, 0.0};
  c.up = {0, 1, 0};
  c.fov_deg = 40;
  c.viewport = {400, 300};
  return c;
}

// A unit sphere at (0.3, 0, 0) seen from +z (its image: a disc of ~100 px radius around (200, 150)).
Scene ball_scene() {
  Scene s;
  s.insert(trispline::test::sphere_object("ball", 12, 6, {0.3, 0.0, 0.0}));
  s.camera = view();
  s.camera_set = true;
  return s;
}

const std::vector<glm::dvec2> kStroke = {{170, 150}, {200, 148}, {230, 152}};
constexpr double kRadius = 25.0;

json stroke_json(const std::vector<glm::dvec2>& pts) {
  json a = json::array();
  for (const glm::dvec2& p : pts) a.push_back({p.x, p.y});
  return a;
}

json paint_line(const std::string& layer, bool erase = false, const std::vector<glm::dvec2>& stroke = kStroke,
                double radius = kRadius) {
  // A limit base (three charts per triangle: the cells the tests count), named as the old default was.
  return {{"cmd", "ddm.paint"},  {"object", "ball"}, {"layer", layer}, {"stroke", stroke_json(stroke)},
          {"radius_px", radius}, {"erase", erase},   {"base", "limit"}};
}

CommandPtr run(Scene& s, const json& line) {
  CommandPtr c = DdmPaintCommand::parse(line, {});
  c->redo(s);
  return c;
}

std::shared_ptr<const DdmLayer> layer_of(const Scene& s, const std::string& name) {
  for (const auto& l : s.find("ball")->ddm_layers)
    if (l->name == name) return l;
  return nullptr;
}

double polyline_distance(glm::dvec2 q, const std::vector<glm::dvec2>& line) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const glm::dvec2 a = line[i], ab = line[i + 1] - a;
    const double t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    best = std::min(best, glm::length(q - (a + t * ab)));
  }
  return best;
}

struct Expected {
  std::set<Key> front;  // centres within the brush, facing the camera
  int back = 0;         // centres within the brush on the far side
};

// Written independently of the command: every layout cell of every chart, its centre on the layer's surface.
Expected expected_cells(const SceneObject& o, const DdmLayer& layer, const Camera& cam,
                        const std::vector<glm::dvec2>& stroke, double radius, const RayCaster* occluder = nullptr) {
  Expected e;
  const glm::dmat4 m = o.transform.matrix();
  const std::vector<DdmInstance> cells = ddm_layout_cells(layer.layout, layer.counts, 1);
  for (int c = 0; c < layer.surface->chart_count(); ++c)
    for (DdmInstance cell : cells) {
      cell.chart = c;
      const glm::dvec2 uv = cell.origin + 0.5 * cell.size;
      const DdmSurfacePoint s = layer.surface->eval(c, uv.x, uv.y);
      const glm::dvec3 p = glm::dvec3(m * glm::dvec4(s.p, 1.0));  // a translation: normals unchanged
      const glm::dvec3 q = cam.project(p);
      if (q.z <= 0 || polyline_distance(glm::dvec2(q), stroke) > radius) continue;
      if (glm::dot(s.n, cam.eye - p) <= 0) {
        ++e.back;
        continue;
      }
      if (occluder && occluder->intersect(cam.eye, p - cam.eye, 0.0, glm::length(p - cam.eye))) continue;
      e.front.insert(key(cell));
    }
  return e;
}

TEST(DdmPaint, StrokeCreatesTheLayerWithExactlyTheVisibleCellsUnderTheBrush) {
  Scene s = ball_scene();
  json line = paint_line("spots");
  line["tile"] = "hex";
  line["counts"] = {2, 2};
  line["height"] = 0.05;
  const CommandPtr c = run(s, line);
  const auto layer = layer_of(s, "spots");
  ASSERT_TRUE(layer);
  EXPECT_EQ(layer->tile_sources, std::vector<std::string>{"hex"});
  EXPECT_EQ(layer->counts, glm::ivec2(2, 2));
  EXPECT_EQ(layer->height, 0.05);
  const Expected e = expected_cells(*s.find("ball"), *layer, view(), kStroke, kRadius);
  ASSERT_GE(e.front.size(), 10u);
  EXPECT_GE(e.back, 10) << "the far side projects under the brush too: the test must be able to see it stay bare";
  EXPECT_EQ(keys(layer->instances), e.front);
  EXPECT_EQ(layer->instances.size(), e.front.size()) << "no cell twice";
  EXPECT_EQ(layer->mesh->vertex_count(), layer->instances.size() * layer->tiles[0].mesh.vertex_count());
  const json st = c->stats();
  EXPECT_EQ(st["created"], true);
  EXPECT_EQ(st["cells_added"], e.front.size());
  EXPECT_EQ(st["cells_removed"], 0);
  EXPECT_EQ(st["tiles"], e.front.size());
  EXPECT_EQ(st["vertices"], layer->mesh->vertex_count());
  EXPECT_TRUE(st.contains("ms"));
  // The line logs the new layer's fields back (it replays on its own); the scene camera was used.
  const json j = c->to_json();
  EXPECT_EQ(j["tile"], "hex");
  EXPECT_EQ(j["counts"], json::parse("[2,2]"));
  EXPECT_EQ(j["radius_px"], kRadius);
  EXPECT_EQ(j["erase"], false);
  EXPECT_FALSE(j.contains("camera"));

  c->undo(s);
  EXPECT_FALSE(layer_of(s, "spots")) << "undo removes the layer the stroke made";
}

TEST(DdmPaint, PaintingAddsOnlyMissingCellsEraseRemovesAndUndoRestoresExactly) {
  Scene s = ball_scene();
  json first = paint_line("t");
  first["tile"] = "hex";
  first["counts"] = {2, 1};
  run(s, first);
  const auto before = layer_of(s, "t");
  const std::vector<DdmInstance> painted = before->instances;

  // A second stroke lower down overlaps the first: only the new cells are added, the old ones stay in order first.
  const std::vector<glm::dvec2> lower = {{170, 170}, {230, 172}};
  const CommandPtr more = run(s, paint_line("t", false, lower));
  const auto after = layer_of(s, "t");
  const Expected e2 = expected_cells(*s.find("ball"), *after, view(), lower, kRadius);
  std::set<Key> both = keys(painted);
  both.insert(e2.front.begin(), e2.front.end());
  EXPECT_EQ(keys(after->instances), both);
  EXPECT_EQ(after->instances.size(), both.size());
  EXPECT_TRUE(std::equal(painted.begin(), painted.end(), after->instances.begin()));
  EXPECT_EQ(more->stats()["cells_added"], both.size() - painted.size());
  EXPECT_GT(more->stats()["touched"].get<std::size_t>(), more->stats()["cells_added"].get<std::size_t>());

  more->undo(s);
  EXPECT_EQ(layer_of(s, "t"), before) << "undo restores the layer itself";
  EXPECT_EQ(layer_of(s, "t")->instances, painted);
  more->redo(s);
  EXPECT_EQ(layer_of(s, "t"), after) << "redo restores the painted layer";

  // Erasing along the first stroke removes exactly its cells; what only the second stroke painted remains.
  const CommandPtr erase = run(s, paint_line("t", true));
  std::set<Key> rest;
  for (const Key& k : both)
    if (!keys(painted).count(k)) rest.insert(k);
  EXPECT_EQ(keys(layer_of(s, "t")->instances), rest);
  EXPECT_EQ(erase->stats()["cells_removed"], painted.size());
  EXPECT_EQ(erase->stats()["cells_added"], 0);
  EXPECT_EQ(erase->to_json()["erase"], true);
  erase->undo(s);
  EXPECT_EQ(layer_of(s, "t")->instances, after->instances) << "undo of an erase restores the instance set exactly";
}

TEST(DdmPaint, CellsBehindAnotherObjectStayBare) {
  Scene s = ball_scene();
  SceneObject wall;
  wall.name = "wall";
  wall.source = "primitive:box";
  wall.rest_mesh = std::make_shared<const TriMesh>(make_box());
  wall.transform.scale = {0.1, 0.12, 0.02};     // make_box is [-1, 1]³
  wall.transform.translate = {0.15, 0.0, 2.0};  // between the eye and the left half of the stroke
  wall.refresh();
  s.insert(wall);
  json line = paint_line("t");
  line["tile"] = "hex";
  line["counts"] = {2, 2};
  run(s, line);
  const auto layer = layer_of(s, "t");
  RayCaster box;
  box.add_mesh(*s.find("wall")->world_mesh);
  box.commit();
  const Expected open = expected_cells(*s.find("ball"), *layer, view(), kStroke, kRadius);
  const Expected e = expected_cells(*s.find("ball"), *layer, view(), kStroke, kRadius, &box);
  ASSERT_LT(e.front.size() + 5, open.front.size()) << "the wall must hide part of the brush's cells";
  ASSERT_FALSE(e.front.empty());
  EXPECT_EQ(keys(layer->instances), e.front);
}

TEST(DdmPaint, SeveralTilesFollowFillsPattern) {
  Scene s = ball_scene();
  const json spec = {
      {"tile", "thorn"}, {"tiles", {"flower"}}, {"layout", "brick"}, {"counts", {3, 2}}, {"height", 0.05}};
  json fill = {{"cmd", "ddm.fill"}, {"object", "ball"}, {"layer", "all"}, {"base", "limit"}};
  fill.update(spec);
  DdmFillCommand::parse(fill, {})->redo(s);
  json line = paint_line("some");
  line.update(spec);
  run(s, line);
  std::set<Key> filled = keys(layer_of(s, "all")->instances);
  const auto painted = layer_of(s, "some");
  ASSERT_FALSE(painted->instances.empty());
  std::set<int> used;
  for (const DdmInstance& c : painted->instances) {
    EXPECT_TRUE(filled.count(key(c))) << "chart " << c.chart << ": the tile a pattern fill gives this cell";
    used.insert(c.tile);
  }
  EXPECT_EQ(used, (std::set<int>{0, 1}));
  EXPECT_EQ(ddm_paint_tile_index(4, 1, 1), 0);
  EXPECT_EQ(ddm_paint_tile_index(4, 1, 2), 1);
  EXPECT_EQ(ddm_paint_tile_index(4, 1, 3), 2);
}

TEST(DdmPaint, AStrokeThatTouchesNothingIsAnErrorAndChangesNothing) {
  Scene s = ball_scene();
  json line = paint_line("t");
  line["tile"] = "hex";
  run(s, line);
  const auto before = layer_of(s, "t");
  for (const char* layer : {"t", "new"}) {
    const CommandPtr c = DdmPaintCommand::parse(paint_line(layer, false, {{5, 5}, {20, 8}}, 4.0), {});
    EXPECT_TRUE(test::throws_command_error([&] { c->redo(s); }, "stroke", "touches no visible cell"))
        << "a stroke in the corner touched something";
    EXPECT_EQ(s.find("ball")->ddm_layers.size(), 1u) << "no layer made";
    EXPECT_EQ(layer_of(s, "t"), before);
  }
  // One point is a dab: valid.
  const CommandPtr dab = run(s, paint_line("t", false, {{200, 150}}, 30.0));
  EXPECT_GT(dab->stats()["touched"].get<int>(), 0);
}

TEST(DdmPaint, BadFieldsNameTheField) {
  Scene s = ball_scene();
  auto field_of = [&](const json& line) { return test::command_field_of<DdmPaintCommand>(s, line); };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  json l = paint_line("t");
  l["radius_px"] = 0.0;
  EXPECT_EQ(field_of(l), "radius_px");
  l["radius_px"] = -3.0;
  EXPECT_EQ(field_of(l), "radius_px");
  l["radius_px"] = nan;
  EXPECT_EQ(field_of(l), "radius_px");
  l = paint_line("t");
  l["stroke"] = json::array();
  EXPECT_EQ(field_of(l), "stroke");
  l["stroke"] = {{1.0, nan}};
  EXPECT_EQ(field_of(l), "stroke");
  l["stroke"] = {{1.0}};
  EXPECT_EQ(field_of(l), "stroke");
  EXPECT_EQ(field_of(paint_line("")), "layer");
  EXPECT_EQ(field_of(paint_line("t", true)), "layer") << "nothing to erase from";
  l = paint_line("t");
  l["object"] = "nobody";
  EXPECT_EQ(field_of(l), "object");
  l = paint_line("t");
  l["counts"] = {0, 1};
  EXPECT_EQ(field_of(l), "counts");
  // 3162² cells a chart pass the layer budget one chart at a time, but not over every chart of the ball: refused from
  // the counts before a cell is made (it once ran 82 s into 5.7 GB and a bad_alloc).
  l = paint_line("t");
  l["counts"] = {3162, 3162};
  EXPECT_EQ(field_of(l), "counts");
  l["counts"] = {100000, 100000};
  EXPECT_EQ(field_of(l), "counts");
  l = paint_line("t");
  l["tile"] = "cactus";
  EXPECT_EQ(field_of(l), "tile");
  l = paint_line("t");
  l["base"] = "teapot_body";
  EXPECT_EQ(field_of(l), "base");
  EXPECT_TRUE(s.find("ball")->ddm_layers.empty());

  // Pixels need a camera: the scene's (camera.set) or the line's own.
  s.camera_set = false;
  EXPECT_EQ(field_of(paint_line("t")), "camera");
  l = paint_line("t");
  l["camera"] = camera_schema().fields_json(view());
  const CommandPtr c = run(s, l);
  EXPECT_GT(c->stats()["cells_added"].get<int>(), 0);
  EXPECT_TRUE(c->to_json().contains("camera"));
  EXPECT_EQ(c->label(), "Paint tiles on ball/t");
}

}  // namespace
}  // namespace trispline::core
