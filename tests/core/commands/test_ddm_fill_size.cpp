// ddm.fill / ddm.paint by tile size (core/commands/ddm_layer_spec.h): cells per chart from each chart's world size, so
// tiles come out of even world size where `counts` gives every chart the same cells; the panel's estimate is the
// fill's count; tile_size with counts, and a tile size too small for the vertex budget, are refused naming the field
// before anything is allocated; on the Stanford bunny (no UVs) with automatic UVs the tiles' world areas stay within
// a factor of 3.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_paint.h"
#include "core/commands/ddm_remove.h"
#include "core/commands/scene_primitive.h"
#include "core/ddm/ddm_chart_size.h"
#include "core/mesh/mesh_io.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

using nlohmann::json;

// World size of a cell: its chart's world size times the cell's share of the chart.
std::vector<glm::dvec2> cell_world_sizes(const DdmLayer& layer, const std::vector<glm::dvec2>& chart_sizes) {
  std::vector<glm::dvec2> out;
  for (const DdmInstance& i : layer.instances)
    out.push_back(chart_sizes.at(static_cast<std::size_t>(i.chart)) * i.size);
  return out;
}

double spread(const std::vector<glm::dvec2>& sizes) {  // largest / smallest cell width
  double lo = 1e300, hi = 0.0;
  for (const glm::dvec2& s : sizes) lo = std::min(lo, s.x), hi = std::max(hi, s.x);
  return hi / lo;
}

TEST(DdmFillSize, TilesOfEvenWorldSizeOnALimitBase) {
  Scene s;
  s.insert(test::sphere_object("ball", 12, 6, glm::dvec3(0.0)));  // charts of many sizes (small at the poles)
  const std::vector<glm::dvec2> charts = ddm_limit_chart_sizes(*s.find("ball")->rest_mesh);
  double smallest = 1e300;
  for (const glm::dvec2& c : charts) smallest = std::min({smallest, c.x, c.y});
  const double tile = smallest / 3.0;  // ≥ 3 tiles across every chart: rounding moves a width by ≤ 1/6

  DdmLayerSpec spec;
  spec.base = DdmBaseKind::limit;
  spec.tiles = {"hex"};
  spec.tile_size = tile;
  const DdmFillEstimate estimate = ddm_fill_estimate(*s.find("ball"), spec);
  json line =
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"even","tile":"hex","layout":"rect",
      "height":0.01})");
  line["tile_size"] = tile;
  auto fill = test::run_line<DdmFillCommand>(s, line);
  EXPECT_DOUBLE_EQ(fill->to_json()["tile_size"].get<double>(), tile);  // logged back
  EXPECT_FALSE(fill->to_json().contains("counts"));
  const DdmLayer& layer = *s.find("ball")->ddm_layers.at(0);
  ASSERT_EQ(layer.chart_counts.size(), charts.size());
  EXPECT_EQ(estimate.cells, layer.instances.size()) << "the estimate is the fill's count";
  EXPECT_EQ(estimate.tile_vertices, layer.mesh->vertex_count());
  EXPECT_FALSE(estimate.upper_bound);
  for (const glm::dvec2& c : cell_world_sizes(layer, charts)) {
    EXPECT_NEAR(c.x / tile, 1.0, 0.18);
    EXPECT_NEAR(c.y / tile, 1.0, 0.18);
  }
  // The same cell count per chart everywhere (counts) spreads the widths by the charts' own spread.
  Scene t;
  t.insert(test::sphere_object("ball", 12, 6, glm::dvec3(0.0)));
  test::run_line<DdmFillCommand>(
      t, json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"c","tile":"hex",
      "layout":"rect","counts":[4,4],"height":0.01})"));
  const double by_counts = spread(cell_world_sizes(*t.find("ball")->ddm_layers.at(0), charts));
  const double by_size = spread(cell_world_sizes(layer, charts));
  std::printf("cell width spread (largest / smallest): by counts %.2f, by tile size %.2f\n", by_counts, by_size);
  EXPECT_LT(by_size, 1.45);
  EXPECT_GT(by_counts, 2.0 * by_size);
  fill->undo(s);
  EXPECT_TRUE(s.find("ball")->ddm_layers.empty());
}

TEST(DdmFillSize, HexAndBrickRowsOnTheTeapotBody) {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})->redo(s);
  for (const char* layout : {"hex", "brick", "rect"}) {
    DdmLayerSpec spec;
    spec.base = DdmBaseKind::teapot_body;
    spec.layout = layout == std::string("hex")     ? DdmLayout::hex
                  : layout == std::string("brick") ? DdmLayout::brick
                                                   : DdmLayout::rect;
    spec.tile_size = 0.25;
    const DdmFillEstimate e = ddm_fill_estimate(*s.find("pot"), spec);
    test::run_line<DdmFillCommand>(s, json::parse(std::string(R"({"cmd":"ddm.fill","object":"pot","layer":"a",
        "tile":"hex","tile_size":0.25,"height":0.02,"base":"teapot_body","layout":")") +
                                                  layout + "\"}"));
    const DdmLayer& layer = *s.find("pot")->ddm_layers.at(0);
    EXPECT_EQ(e.cells, layer.instances.size()) << layout;
    const glm::dvec2 size = ddm_chart_size(*layer.surface, 0);
    const DdmInstance& cell = layer.instances.front();
    EXPECT_NEAR(size.x * cell.size.x / 0.25, 1.0, 0.15) << layout;  // round the pot
    EXPECT_NEAR(size.y * cell.size.y / 0.25, 1.0, 0.25) << layout;  // up the pot: few rows, rounding shows more
  }
}

TEST(DdmFillSize, BadSizesAreRefusedNamingTheField) {
  Scene s;
  s.insert(test::sphere_object("ball", 16, 8, glm::dvec3(0.0)));
  auto field = [&](const std::string& extra) {
    return test::command_field_of<DdmFillCommand>(
        s,
        json::parse(
            R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect","height":0.1)" +
            extra + "}"));
  };
  EXPECT_EQ(field(R"(,"tile_size":0.1,"counts":[2,2])"), "tile_size");  // not both
  EXPECT_EQ(field(""), "counts");                                       // neither
  EXPECT_EQ(field(R"(,"tile_size":0)"), "tile_size");
  EXPECT_EQ(field(R"(,"tile_size":-1)"), "tile_size");
  // Far too small for the vertex budget: refused with the count before any cell exists, at once.
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        DdmFillCommand::parse(
            json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn",
            "layout":"rect","height":0.1,"tile_size":1e-7})"),
            {})
            ->redo(s);
      },
      "tile_size", "tile vertices (at most 10000000)"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  EXPECT_TRUE(s.find("ball")->ddm_layers.empty()) << "the scene is unchanged";
  // A line's own hard limit: refused above it with the count, naming the field that made the tiles.
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        DdmFillCommand::parse(
            json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn",
            "layout":"rect","height":0.1,"counts":[1,1],"max_vertices":100000})"),
            {})
            ->redo(s);
      },
      "counts", "tile vertices (at most 100000, max_vertices)"));
  EXPECT_EQ(field(R"(,"counts":[1,1],"max_vertices":0)"), "max_vertices");
  EXPECT_EQ(field(R"(,"counts":[1,1],"max_vertices":20000000)"), "max_vertices");  // above the layer budget
  EXPECT_EQ(field(R"(,"counts":[1,1],"max_vertices":10000000)"), "(accepted)");
  DdmLayerSpec spec;
  spec.base = DdmBaseKind::limit;
  spec.tile_size = 1e-7;
  EXPECT_TRUE(
      test::throws_command_error([&] { (void)ddm_fill_estimate(*s.find("ball"), spec); }, "tile_size", "tiles ×"));
}

// On a uv base the vertex budget holds the tiles the UV islands keep, not the layout's cells before pruning: a tile
// size whose cells × tile vertices exceed max_vertices is laid when the kept tiles fit, and refused naming the field,
// the scene unchanged, when they do not.
TEST(DdmFillSize, TheBudgetOnAUvBaseCountsTheTilesTheIslandsKeep) {
  Scene s;
  s.insert(test::sphere_object("ball", 16, 8, glm::dvec3(0.0)));
  const std::string line = R"({"cmd":"ddm.fill","base":"auto_uv","object":"ball","layer":"x","tile":"thorn",
      "layout":"rect","height":0.05,"tile_size":0.15)";
  DdmLayerSpec spec;
  spec.base = DdmBaseKind::auto_uv;
  spec.tile_size = 0.15;
  const DdmFillEstimate e = ddm_fill_estimate(*s.find("ball"), spec);
  ASSERT_TRUE(e.upper_bound);
  auto fill = test::run_line<DdmFillCommand>(s, json::parse(line + "}"));
  const DdmLayer& layer = *s.find("ball")->ddm_layers.at(0);
  const std::size_t per_tile = layer.tiles.at(0).mesh.vertex_count();
  const std::size_t kept = layer.instances.size() * per_tile;
  ASSERT_GT(e.tile_vertices, kept) << "the islands prune some cells";
  EXPECT_EQ(layer.mesh->vertex_count(), kept);
  // max_vertices between the kept tiles and the cells laid: accepted before, refused by the cells, now laid.
  Scene t;
  t.insert(test::sphere_object("ball", 16, 8, glm::dvec3(0.0)));
  test::run_line<DdmFillCommand>(t, json::parse(line + ",\"max_vertices\":" + std::to_string(kept) + "}"));
  EXPECT_EQ(t.find("ball")->ddm_layers.at(0)->instances.size(), layer.instances.size());
  // One vertex fewer than the kept tiles: refused, naming tile_size and both counts, nothing added.
  Scene u;
  u.insert(test::sphere_object("ball", 16, 8, glm::dvec3(0.0)));
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        DdmFillCommand::parse(json::parse(line + ",\"max_vertices\":" + std::to_string(kept - 1) + "}"), {})->redo(u);
      },
      "tile_size", std::to_string(layer.instances.size()) + " tiles on the UV islands"));
  EXPECT_TRUE(u.find("ball")->ddm_layers.empty()) << "the scene is unchanged";
}

// A line without "base" means what the Tile Paint panel shows: the object's own base (ddm_default_base), named in
// the report — on the teapot primitive its body patches, on a mesh without texture coordinates automatic ones.
TEST(DdmFillSize, ALineWithoutBaseGetsTheObjectsBaseAsThePanelDoes) {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})->redo(s);
  s.insert(test::sphere_object("ball", 16, 8, glm::dvec3(3.0, 0.0, 0.0)));
  ASSERT_TRUE(s.find("ball")->rest_mesh->uvs.empty());
  for (const char* object : {"pot", "ball"}) {
    SCOPED_TRACE(object);
    const DdmBaseKind panel = ddm_default_base(*s.find(object));
    auto fill = test::run_line<DdmFillCommand>(
        s, json::parse(std::string(R"({"cmd":"ddm.fill","layer":"a","tile":"hex","layout":"rect","tile_size":0.2,
            "height":0.02,"object":")") +
                       object + "\"}"));
    EXPECT_EQ(fill->stats().at("base"), ddm_base_name(panel)) << "report.json says which base it chose";
    const DdmLayer& by_default = *s.find(object)->ddm_layers.at(0);
    EXPECT_EQ(by_default.base, panel);
    const std::size_t tiles = by_default.instances.size();
    // The same line naming the panel's base: the same layer.
    auto named = test::run_line<DdmFillCommand>(
        s, json::parse(std::string(R"({"cmd":"ddm.fill","layer":"a","tile":"hex","layout":"rect","tile_size":0.2,
            "height":0.02,"base":")") +
                       ddm_base_name(panel) + R"(","object":")" + object + "\"}"));
    EXPECT_EQ(s.find(object)->ddm_layers.at(0)->instances.size(), tiles);
    // limit, the old default, lays three charts per triangle: many more tiles at the same size.
    auto limit = test::run_line<DdmFillCommand>(
        s, json::parse(std::string(R"({"cmd":"ddm.fill","layer":"a","tile":"hex","layout":"rect","tile_size":0.2,
            "height":0.02,"base":"limit","object":")") +
                       object + "\"}"));
    EXPECT_GT(s.find(object)->ddm_layers.at(0)->instances.size(), tiles);
  }
  EXPECT_EQ(ddm_default_base(*s.find("pot")), DdmBaseKind::teapot_body);
  EXPECT_EQ(ddm_default_base(*s.find("ball")), DdmBaseKind::auto_uv);
}

TEST(DdmFillSize, PaintingALayerLaidBySize) {
  Scene s;
  s.insert(test::sphere_object("ball", 16, 8, glm::dvec3(0.0)));
  s.camera = test::front_camera(4.0, 40.0, {400, 400});
  s.camera_set = true;
  auto paint =
      test::run_line<DdmPaintCommand>(s, json::parse(R"({"cmd":"ddm.paint","base":"limit","object":"ball","layer":"p",
      "tile":"hex","tile_size":0.05,"height":0.01,"stroke":[[200,200]],"radius_px":30})"));
  EXPECT_DOUBLE_EQ(paint->to_json()["tile_size"].get<double>(), 0.05);
  const DdmLayer& layer = *s.find("ball")->ddm_layers.at(0);
  ASSERT_FALSE(layer.instances.empty());
  ASSERT_EQ(layer.chart_counts.size(), 3 * s.find("ball")->rest_mesh->triangle_count());
  for (const DdmInstance& i : layer.instances) {  // each painted cell is a cell of its own chart's layout
    const glm::ivec2 n = layer.chart_counts.at(static_cast<std::size_t>(i.chart));
    EXPECT_DOUBLE_EQ(i.size.x, 1.0 / n.x);
    EXPECT_DOUBLE_EQ(i.size.y, 1.0 / n.y);
  }
  const std::vector<glm::dvec2> charts = ddm_limit_chart_sizes(*s.find("ball")->rest_mesh);
  for (const glm::dvec2& c : cell_world_sizes(layer, charts)) EXPECT_NEAR(c.x / 0.05, 1.0, 0.5);
  // A new layer's candidate cells are weighed too: a tile size far too small is refused, naming it.
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        DdmPaintCommand::parse(
            json::parse(R"({"cmd":"ddm.paint","base":"limit","object":"ball","layer":"q","tile_size":1e-6,
            "stroke":[[200,200]],"radius_px":30})"),
            {})
            ->redo(s);
      },
      "tile_size", "cells to paint (at most 10000000)"));
}

#ifdef TRISPLINE_HAVE_BUNNY
// World area of a tile's cell on the layer's maps: the mean of |S_u × S_v| over 4 × 4 points times the cell's area.
double cell_world_area(const DdmMapsBase& base, const DdmInstance& i) {
  double sum = 0.0;
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      const DdmSurfacePoint p =
          base.eval(i.chart, i.origin.x + (a + 0.5) / 4 * i.size.x, i.origin.y + (b + 0.5) / 4 * i.size.y);
      sum += glm::length(glm::cross(p.du, p.dv));
    }
  return sum / 16.0 * i.size.x * i.size.y;
}

TEST(DdmFillSize, EvenTilesOnTheBunnyWithAutomaticUvs) {
  Scene s;
  SceneObject bunny;
  bunny.name = "bunny";
  bunny.source = "bunny.obj";
  bunny.rest_mesh =
      std::make_shared<const TriMesh>(load_mesh(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/bunny.obj"));
  ASSERT_TRUE(bunny.rest_mesh->uvs.empty()) << "the bunny has no texture coordinates";
  bunny.refresh();
  s.insert(bunny);
  EXPECT_EQ(ddm_default_base(*s.find("bunny")), DdmBaseKind::auto_uv);
  double area = 0.0;
  const TriMesh& m = *bunny.rest_mesh;
  for (const glm::uvec3& t : m.triangles)
    area += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
  const double tile = std::sqrt(area / 1500.0);  // about 1,500 tiles
  DdmLayerSpec spec;
  spec.base = DdmBaseKind::auto_uv;
  spec.tile_size = tile;
  const auto t0 = std::chrono::steady_clock::now();
  const DdmFillEstimate e = ddm_fill_estimate(*s.find("bunny"), spec);  // unwraps (cached for the fill)
  const double estimate_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(e.upper_bound);
  auto fill = test::run_line<DdmFillCommand>(s, json::parse(R"({"cmd":"ddm.fill","object":"bunny","layer":"t",
      "tile":"hex","layout":"rect","base":"auto_uv","height":0.002,"tile_size":)" +
                                                            std::to_string(tile) + "}"));
  const DdmLayer& layer = *s.find("bunny")->ddm_layers.at(0);
  EXPECT_LE(layer.instances.size(), e.cells);
  // Coverage: cells straddling a seam of the atlas are pruned (ddm_cell_continuous), the rest cover most of the
  // surface: at least 60 % of the ~1,500 tiles its area holds.
  EXPECT_GT(double(layer.instances.size()), 0.6 * 1500.0);
  const DdmMapsBase base(layer.maps);
  std::vector<double> areas;
  for (const DdmInstance& i : layer.instances) areas.push_back(cell_world_area(base, i));
  std::sort(areas.begin(), areas.end());
  const auto at = [&](double q) {
    return areas[static_cast<std::size_t>(q * double(areas.size() - 1))] / (tile * tile);
  };
  std::printf(
      "bunny, auto UVs, tile size %.4g: %zu tiles (estimate up to %zu; %.0f ms to unwrap and estimate, fill "
      "%.0f ms), %s charts, area distortion p95 %s; tile world area / tile_size²: min %.3f p5 %.3f median "
      "%.3f p95 %.3f max %.3f, largest / smallest %.2f\n",
      tile, areas.size(), e.cells, estimate_ms, fill->stats()["ms"].get<double>(),
      fill->stats()["uv_charts"].dump().c_str(), fill->stats()["uv_area_distortion_p95"].dump().c_str(), at(0.0),
      at(0.05), at(0.5), at(0.95), at(1.0), areas.back() / areas.front());
  EXPECT_LE(areas.back() / areas.front(), 3.0);
  EXPECT_NEAR(at(0.5), 1.0, 0.2);
}
#endif

}  // namespace
}  // namespace trispline::core
