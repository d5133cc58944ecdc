// DDM P/N maps (core/ddm/ddm_pn_maps.h, seed §5.3.1–5.3.2, §5.4.1) and layers (ddm_layer.h): the sampled base of a
// plane is the plane, sampled bases converge to the exact base at second order, the teapot body is one periodic chart,
// the tile transform rotates tiles rigidly, UV rasterisation with its diffusion fill and validity bitmap, layers that
// grow their maps when painted, several tiles per layer, texture-space offset animation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/scene/primitives.h"
#include "tests/core/ddm/ddm_test_patches.h"

namespace trispline::core {
namespace {

using test::bump_patch;
using test::flat_patch;

double max_distance(const TriMesh& a, const TriMesh& b) {
  EXPECT_EQ(a.vertex_count(), b.vertex_count());
  double d = 0.0;
  for (std::size_t v = 0; v < std::min(a.vertex_count(), b.vertex_count()); ++v)
    d = std::max(d, glm::length(a.positions[v] - b.positions[v]));
  return d;
}

TEST(DdmMaps, SampledPlaneReproducesTheTile) {
  const DdmSplineBase plane({flat_patch(3.0, 2.0)});
  auto maps = std::make_shared<const DdmMaps>(ddm_sample_maps(plane, {0}, {5, 4}));
  EXPECT_EQ(maps->slot_count(), 1);
  EXPECT_NEAR(maps->base_size, std::sqrt(13.0), 1e-6);
  const DdmTile thorn = make_ddm_tile("thorn");
  const auto cells = ddm_layout_cells(DdmLayout::rect, {3, 2}, 1);
  const TriMesh exact = ddm_evaluate(plane, thorn, cells, 0.5);
  const TriMesh sampled = ddm_evaluate(DdmMapsBase(maps), thorn, cells, 0.5);
  EXPECT_LT(max_distance(exact, sampled), 1e-6);  // bilinear interpolation is exact on a bilinear patch (float data)
  for (std::size_t v = 0; v < exact.vertex_count(); v += 17)
    EXPECT_NEAR(glm::length(exact.normals[v] - sampled.normals[v]), 0.0, 1e-6);
}

TEST(DdmMaps, SampledBaseConvergesAtSecondOrder) {
  const DdmSplineBase bump({bump_patch()});
  const DdmTile thorn = make_ddm_tile("thorn");
  const auto cells = ddm_layout_cells(DdmLayout::rect, {2, 2}, 1);
  const TriMesh exact = ddm_evaluate(bump, thorn, cells, 0.2);
  double previous = 0.0;
  for (int r : {9, 17, 33, 65}) {
    const auto maps = std::make_shared<const DdmMaps>(ddm_sample_maps(bump, {0}, {r, r}));
    const double e = max_distance(exact, ddm_evaluate(DdmMapsBase(maps), thorn, cells, 0.2));
    if (previous > 0.0) EXPECT_LT(e, previous / 3.0) << r;  // h² convergence: ≈ ¼ per halving of the spacing
    previous = e;
  }
  EXPECT_LT(previous, 1e-3 * 3.0);
  EXPECT_THROW(ddm_sample_maps(bump, {0}, {1, 9}), std::invalid_argument);
  EXPECT_THROW(ddm_sample_maps(bump, {3}, {9, 9}), std::invalid_argument);
  EXPECT_THROW(DdmMapsBase(std::make_shared<const DdmMaps>(ddm_sample_maps(bump, {}, {9, 9}))).eval(0, 0.5, 0.5),
               std::out_of_range);  // a chart that was not sampled
}

TEST(DdmMaps, TeapotBodyIsOnePeriodicChart) {
  const auto patches = teapot_body_patches();
  const DdmSplineBase body(patches, {4, 2}, {true, false});
  ASSERT_EQ(body.chart_count(), 1);
  EXPECT_TRUE(body.periodic().x);
  // Chart (u, v) in patch (i, j) is that patch at (4u − i, 2v − j); derivatives scale by (4, 2).
  const DdmSplineBase each(patches);
  const DdmSurfacePoint a = body.eval(0, 0.3, 0.8), b = each.eval(1 + 4 * 1, 4 * 0.3 - 1, 2 * 0.8 - 1);
  EXPECT_NEAR(glm::length(a.p - b.p), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(a.du - 4.0 * b.du), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(a.dv - 2.0 * b.dv), 0.0, 1e-9);
  // Round the pot: u = 1 meets u = 0, and u wraps.
  for (double v : {0.1, 0.5, 0.9}) {
    EXPECT_NEAR(glm::length(body.eval(0, 1.0 - 1e-9, v).p - body.eval(0, 0.0, v).p), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(body.eval(0, 1.25, v).p - body.eval(0, 0.25, v).p), 0.0, 1e-12);
  }
  EXPECT_THROW(DdmSplineBase(patches, {3, 2}), std::invalid_argument);
}

TEST(DdmMaps, TileTransformRotatesTheTileRigidly) {
  const DdmSplineBase plane({flat_patch(1.0, 1.0)});
  const DdmTile chain = make_ddm_tile("chain");
  DdmTileTransform quarter;
  quarter.rotate_deg = 90.0;
  quarter.shift = {0.1, 0.0};
  const TriMesh out = ddm_evaluate(plane, {chain}, {DdmInstance{}}, 1.0, quarter);
  for (std::size_t v = 0; v < chain.mesh.vertex_count(); ++v) {
    const glm::dvec3 t = chain.mesh.positions[v], n = chain.mesh.normals[v];
    const glm::dvec3 want(0.5 - (t.y - 0.5) + 0.1, 0.5 + (t.x - 0.5), t.z);  // R(90°)·(x − ½, y − ½) + ½ + shift
    ASSERT_NEAR(glm::length(out.positions[v] - want), 0.0, 1e-12) << v;
    ASSERT_NEAR(glm::length(out.normals[v] - glm::dvec3(-n.y, n.x, n.z)), 0.0, 1e-12) << v;
  }
  DdmTileTransform half;
  half.scale = {0.5, 0.5};
  const TriMesh small = ddm_evaluate(plane, {chain}, {DdmInstance{}}, 1.0, half);
  EXPECT_NEAR(small.positions[0].x, 0.25 + 0.5 * chain.mesh.positions[0].x, 1e-12);
}

// A plane 2 × 3 (x = 4u, y = 6v) with its uvs on [0, ½]²: the UV maps reproduce it where covered, fill the rest, prune
// outside cells.
TEST(DdmMaps, UvRasterisationFillsAndPrunes) {
  TriMesh plane = make_plane(4);
  ASSERT_EQ(plane.uvs.size(), plane.vertex_count());
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) {
    const glm::dvec2 uv = plane.uvs[v];
    plane.positions[v] = {2.0 * uv.x, 3.0 * uv.y, 0.0};
    plane.normals[v] = {0, 0, 1};
    plane.uvs[v] = 0.5 * uv;
  }
  auto maps = std::make_shared<const DdmMaps>(ddm_rasterize_uv_maps(plane, 65));
  EXPECT_TRUE(maps->valid[0]);
  EXPECT_FALSE(maps->valid[64 * 65 + 64]);
  const DdmMapsBase base(maps);
  const DdmSurfacePoint q = base.eval(0, 0.2, 0.4);
  EXPECT_NEAR(glm::length(q.p - glm::dvec3(0.8, 2.4, 0.0)), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(q.du - glm::dvec3(4.0, 0, 0)), 0.0, 1e-5);  // ∂S/∂u: 2 world units per ½ uv
  EXPECT_NEAR(glm::length(q.dv - glm::dvec3(0, 6.0, 0)), 0.0, 1e-5);
  EXPECT_NEAR(glm::length(q.n - glm::dvec3(0, 0, 1)), 0.0, 1e-6);
  // Filled samples continue the border values (diffusion), so they are finite and close to the nearest edge.
  const DdmSurfacePoint out = base.eval(0, 0.9, 0.9);
  EXPECT_TRUE(std::isfinite(out.p.x));
  EXPECT_NEAR(out.p.x, 2.0, 0.05);  // the covered border is at x = 4 · ½
  EXPECT_TRUE(ddm_cell_valid(*maps, {0, {0.0, 0.0}, {0.5, 0.5}}));
  EXPECT_FALSE(ddm_cell_valid(*maps, {0, {0.6, 0.6}, {0.3, 0.3}}));
  TriMesh no_uv = plane;
  no_uv.uvs.clear();
  EXPECT_THROW(ddm_rasterize_uv_maps(no_uv, 65), std::invalid_argument);
  TriMesh nan_uv = plane;
  nan_uv.uvs[3].x = std::nan("");
  EXPECT_THROW(ddm_rasterize_uv_maps(nan_uv, 65), std::invalid_argument);
}

DdmLayer sphere_layer(const std::vector<DdmInstance>& instances) {
  DdmLayer layer;
  layer.name = "t";
  layer.tiles = {make_ddm_tile("thorn"), make_ddm_tile("hex")};
  layer.tile_sources = {"thorn", "hex"};
  layer.surface = std::make_shared<DdmSubdivBase>(make_sphere(8, 4));
  layer.instances = instances;
  layer.height = 0.1;
  ddm_layer_finish(layer, {9, 9});
  return layer;
}

TEST(DdmLayer, PaintingGrowsTheMapsAndKeepsTheSampledCharts) {
  const DdmLayer layer = sphere_layer({{0, {0, 0}, {1, 1}, 0}});
  EXPECT_EQ(layer.maps->slot_count(), 1);
  EXPECT_EQ(layer.mesh->vertex_count(), 626u);
  const auto grown = ddm_layer_with_instances(layer, {{0, {0, 0}, {1, 1}, 0}, {7, {0, 0}, {1, 1}, 1}});
  EXPECT_EQ(grown->maps->slot_count(), 2);
  EXPECT_EQ(grown->maps->chart_of_slot, (std::vector<int>{0, 7}));
  for (std::size_t k = 0; k < layer.maps->samples.size(); ++k)
    ASSERT_EQ(grown->maps->samples[k], layer.maps->samples[k]);
  EXPECT_EQ(grown->mesh->vertex_count(), 626u + make_ddm_tile("hex").mesh.vertex_count());
  for (std::size_t v = 0; v < 626; ++v) ASSERT_EQ(grown->mesh->positions[v], layer.mesh->positions[v]);
  EXPECT_THROW(ddm_layer_with_instances(layer, {{0, {0, 0}, {1, 1}, 2}}), std::invalid_argument);  // tile 2 of 2
  EXPECT_THROW(ddm_layer_with_instances(layer, {{9999, {0, 0}, {1, 1}, 0}}), std::invalid_argument);
}

void expect_same_bits(const TriMesh& a, const TriMesh& b) {
  ASSERT_EQ(a.vertex_count(), b.vertex_count());
  ASSERT_EQ(a.triangle_count(), b.triangle_count());
  for (std::size_t v = 0; v < a.vertex_count(); ++v) {
    ASSERT_EQ(a.positions[v], b.positions[v]) << v;
    ASSERT_EQ(a.normals[v], b.normals[v]) << v;
  }
  for (std::size_t f = 0; f < a.triangle_count(); ++f) ASSERT_EQ(a.triangles[f], b.triangles[f]) << f;
}

// A chart whose S_u × S_v points against N (texture coordinates mirrored on the surface, as the plane primitive's
// are: u along x, v along z, N = +y) maps tiles with det J < 0: the copies still stand on the side N points to, wound
// counter-clockwise from outside, their normals pointing out — as on the same plane with unmirrored coordinates.
TEST(DdmMaps, TilesOnAMirroredChartAreNotInsideOut) {
  TriMesh plane = make_plane(4);
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) {
    plane.positions[v] = {plane.uvs[v].x, 0.0, plane.uvs[v].y};
    plane.normals[v] = {0, 1, 0};
  }
  const DdmTile hex = make_ddm_tile("hex");
  for (const bool mirrored : {true, false}) {
    TriMesh base_mesh = plane;
    if (!mirrored)
      for (glm::dvec2& uv : base_mesh.uvs) uv.y = 1.0 - uv.y;
    const DdmMapsBase base(std::make_shared<const DdmMaps>(ddm_rasterize_uv_maps(base_mesh, 33)));
    ASSERT_EQ(glm::dot(glm::cross(base.eval(0, 0.5, 0.5).du, base.eval(0, 0.5, 0.5).dv), glm::dvec3(0, 1, 0)) < 0,
              mirrored);
    const TriMesh out = ddm_evaluate(base, hex, {{0, {0.25, 0.25}, {0.5, 0.5}}}, 0.2);
    double lowest = 1e300, up_area = 0.0;
    for (std::size_t f = 0; f < out.triangle_count(); ++f) {
      const glm::uvec3 t = out.triangles[f];
      const glm::dvec3 a = out.positions[t.x], b = out.positions[t.y], c = out.positions[t.z];
      const glm::dvec3 face = glm::cross(b - a, c - a);
      const glm::dvec3 n = out.normals[t.x] + out.normals[t.y] + out.normals[t.z];
      if (glm::length(face) > 1e-12) EXPECT_GT(glm::dot(face, n), 0.0) << "face " << f << " mirrored " << mirrored;
      up_area += face.y;  // Σ of the faces' y-components: the projected area seen from above, > 0 when outward
      lowest = std::min({lowest, a.y, b.y, c.y});
    }
    EXPECT_GE(lowest, -1e-9) << "the copy stands above the plane, mirrored " << mirrored;
    EXPECT_NEAR(up_area, 0.0, 1e-9) << "a closed tile's projected areas cancel";
    double top = 0.0;  // the faces at the copy's top face up
    for (std::size_t f = 0; f < out.triangle_count(); ++f) {
      const glm::uvec3 t = out.triangles[f];
      const double y = (out.positions[t.x].y + out.positions[t.y].y + out.positions[t.z].y) / 3.0;
      if (y > 0.5 * 0.2 * 0.1)
        top += glm::cross(out.positions[t.y] - out.positions[t.x], out.positions[t.z] - out.positions[t.x]).y;
    }
    EXPECT_GT(top, 0.0) << "mirrored " << mirrored;
  }
}

TEST(DdmLayer, PaintAndEraseReuseTheHeldTilesBitForBit) {
  // Strokes evaluate only the cells they add; the copied vertices must be exactly those a whole evaluation gives, on
  // a layer with two tiles, a metamorphosis at α(0) = 0.3, an offset and a texture-space transform.
  DdmLayer layer = sphere_layer({});
  layer.morph_tiles = {make_ddm_tile("flower"), make_ddm_tile("hex")};
  layer.alpha = 0.3;
  layer.offset_keys = {{0.0, {0.05, -0.02, 0}, KeyInterpolation::linear}};
  layer.transform.rotate_deg = 20.0;
  layer.transform.scale = {0.8, 0.9};
  layer.instances = ddm_layout_cells(DdmLayout::brick, {2, 2}, 12);
  for (std::size_t k = 0; k < layer.instances.size(); ++k) layer.instances[k].tile = static_cast<int>(k % 2);
  ddm_layer_finish(layer, {9, 9});
  ASSERT_EQ(layer.maps->slot_count(), 12);

  std::vector<DdmInstance> painted = layer.instances;  // a stroke adds cells on sampled and on new charts
  for (const DdmInstance& c : ddm_layout_cells(DdmLayout::brick, {2, 2}, 40))
    if (c.chart >= 10 && c.chart < 30 && c.origin.x == 0.0) painted.push_back({c.chart, c.origin, c.size, c.chart % 2});
  const auto grown = ddm_layer_with_instances(layer, painted);
  EXPECT_GT(grown->maps->slot_count(), 12);
  expect_same_bits(*grown->mesh, ddm_layer_mesh(*grown, 0.0));

  std::vector<DdmInstance> erased;  // an erase removes cells from the middle
  for (std::size_t k = 0; k < painted.size(); ++k)
    if (k % 3 != 1) erased.push_back(painted[k]);
  const auto thinned = ddm_layer_with_instances(*grown, erased);
  expect_same_bits(*thinned->mesh, ddm_layer_mesh(*thinned, 0.0));
  const auto emptied = ddm_layer_with_instances(*thinned, {});
  EXPECT_EQ(emptied->mesh->vertex_count(), 0u);
}

TEST(DdmLayer, OffsetAndMetamorphosisOverTime) {
  DdmLayer layer;
  layer.name = "pot";
  layer.tiles = {make_ddm_tile("thorn")};
  layer.morph_tiles = {make_ddm_tile("flower")};
  layer.surface = std::make_shared<DdmSplineBase>(teapot_body_patches(), glm::ivec2(4, 2), glm::bvec2(true, false));
  layer.base = DdmBaseKind::teapot_body;
  layer.instances = ddm_layout_cells(DdmLayout::rect, {8, 3}, 1);
  layer.height = 0.05;
  layer.alpha_keys = {{0.0, {0.0, 0, 0}, KeyInterpolation::linear}, {2.0, {1.0, 0, 0}, KeyInterpolation::linear}};
  layer.offset_velocity = {0.125, 0.0};  // one cell (1/8 of the way round) per second
  ddm_layer_finish(layer, {129, 65});
  EXPECT_TRUE(layer.animated());
  EXPECT_DOUBLE_EQ(layer.alpha_at(1.0), 0.5);
  // At t = 0 the thorns; at t = 2 the flowers moved two cells round the pot: cells 2 further on hold the t = 0 …
  const TriMesh t0 = ddm_layer_mesh(layer, 0.0), t2 = ddm_layer_mesh(layer, 2.0);
  EXPECT_LT(max_distance(t0, *layer.mesh), 1e-15);
  DdmLayer flowers = layer;
  flowers.tiles = flowers.morph_tiles;
  flowers.morph_tiles.clear(), flowers.alpha_keys.clear(), flowers.offset_velocity = {0, 0};
  const TriMesh still = ddm_layer_mesh(flowers, 0.0);
  const std::size_t nv = layer.tiles[0].mesh.vertex_count();
  // … flower instance k at t = 2 sits where flower instance k + 2 (same row) sits without offset.
  for (std::size_t k : {0u, 3u, 9u}) {
    const std::size_t moved = (k / 8) * 8 + (k % 8 + 2) % 8;
    for (std::size_t v = 0; v < nv; v += 25)
      ASSERT_NEAR(glm::length(t2.positions[k * nv + v] - still.positions[moved * nv + v]), 0.0, 1e-5) << k << " " << v;
  }
}

}  // namespace
}  // namespace trispline::core
