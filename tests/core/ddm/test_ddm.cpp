// DDM on the CPU (core/ddm; seed ch. 5): generated tiles are closed 2-manifolds in canonical space, canonical tiles
// from meshes, layouts, T(u,v,w) = S + n·w on a plane (the tile itself: a rigid map) and on curved patches (offset
// along the normal, exact normals), metamorphosis (Eq. 5.3), the teapot body's charts, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "core/ddm/ddm_base.h"
#include "core/ddm/ddm_tile.h"
#include "core/scene/primitives.h"
#include "tests/core/ddm/ddm_test_patches.h"
#include "tests/mesh_topology.h"

namespace trispline::core {
namespace {

using test::bump_patch;  // tests/core/ddm/ddm_test_patches.h
using test::flat_patch;

TEST(DdmTile, GeneratedTilesAreClosedManifoldsInTheCanonicalCell) {
  for (const char* kind : {"thorn", "flower", "chain", "hex", "hair"}) {
    const DdmTile t = make_ddm_tile(kind);
    ASSERT_GT(t.mesh.triangle_count(), 0u) << kind;
    ASSERT_EQ(t.mesh.normals.size(), t.mesh.vertex_count()) << kind;
    Aabb box;
    for (const glm::dvec3& p : t.mesh.positions) box.extend(p);
    EXPECT_GE(box.lo.x, -1e-12) << kind;
    EXPECT_LE(box.hi.x, 1.0 + 1e-12) << kind;
    EXPECT_GE(box.lo.y, -1e-12) << kind;
    EXPECT_LE(box.hi.y, 1.0 + 1e-12) << kind;
    EXPECT_GE(box.lo.z, -1e-12) << kind;
    EXPECT_GT(box.hi.z, 0.1) << kind;
    if (std::string(kind) == "hex") continue;  // flat faces: split vertices per face, closed by position only
    const test::Topology topo = test::topology(t.mesh);
    EXPECT_EQ(topo.boundary_edges, 0u) << kind;
    EXPECT_EQ(topo.nonmanifold_edges, 0u) << kind;
    EXPECT_EQ(topo.repeated_halfedges, 0u) << kind;
    // Outward: the signed volume is positive.
    double vol = 0.0;
    for (const glm::uvec3& f : t.mesh.triangles)
      vol += glm::dot(t.mesh.positions[f.x], glm::cross(t.mesh.positions[f.y], t.mesh.positions[f.z])) / 6.0;
    EXPECT_GT(vol, 0.0) << kind;
  }
  EXPECT_EQ(make_ddm_tile("thorn").mesh.vertex_count(), 626u);
  // Hair (seed Fig. 5.10): 32 strands of 8 rings × 4 points plus a root and a tip, 0.55–0.95 tall, the same bit for
  // bit each time it is made.
  const DdmTile hair = make_ddm_tile("hair");
  EXPECT_EQ(hair.mesh.vertex_count(), 32u * (8u * 4u + 2u));
  Aabb hair_box;
  for (const glm::dvec3& p : hair.mesh.positions) hair_box.extend(p);
  EXPECT_GT(hair_box.hi.z, 0.55);
  EXPECT_LE(hair_box.hi.z, 0.95 + 1e-12);
  EXPECT_EQ(make_ddm_tile("hair").mesh.positions, hair.mesh.positions);
  EXPECT_NO_THROW(require_same_ddm_topology(make_ddm_tile("thorn"), make_ddm_tile("flower")));
  EXPECT_THROW(require_same_ddm_topology(make_ddm_tile("thorn"), make_ddm_tile("chain")), std::invalid_argument);
  EXPECT_THROW(make_ddm_tile("spiral"), std::invalid_argument);
}

TEST(DdmTile, CanonicalTileFillsTheCellAndKeepsProportions) {
  TriMesh box = make_primitive(PrimitiveKind::Box);  // [-1,1]³
  for (glm::dvec3& p : box.positions) p = glm::dvec3(4.0, 1.0, 0.5) + p * glm::dvec3(2.0, 1.0, 0.5);
  const DdmTile t = canonical_ddm_tile(box, "brick");
  Aabb b;
  for (const glm::dvec3& p : t.mesh.positions) b.extend(p);
  EXPECT_NEAR(b.lo.x, 0.0, 1e-15);
  EXPECT_NEAR(b.hi.x, 1.0, 1e-15);
  EXPECT_NEAR(b.hi.y, 1.0, 1e-15);
  EXPECT_NEAR(b.hi.z, 1.0 / 4.0, 1e-15);  // z extent 1 over the larger span 4
  for (const glm::dvec3& n : t.mesh.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);

  TriMesh bad = box;
  bad.positions[3].y = std::nan("");
  try {
    canonical_ddm_tile(bad, "nan");
    FAIL() << "a NaN tile must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
  TriMesh flat = box;
  for (glm::dvec3& p : flat.positions) p.y = 0.0;
  EXPECT_THROW(canonical_ddm_tile(flat, "flat"), std::invalid_argument);
  EXPECT_THROW(canonical_ddm_tile(TriMesh{}, "empty"), std::invalid_argument);
}

TEST(DdmLayout, RectBrickAndHexCells) {
  const auto rect = ddm_layout_cells(DdmLayout::rect, {4, 3}, 2);
  ASSERT_EQ(rect.size(), 24u);
  EXPECT_EQ(rect[5], (DdmInstance{0, {0.25, 1.0 / 3.0}, {0.25, 1.0 / 3.0}}));
  EXPECT_EQ(rect[12].chart, 1);
  const auto brick = ddm_layout_cells(DdmLayout::brick, {4, 3}, 1);
  ASSERT_EQ(brick.size(), 4u + 3u + 4u);
  EXPECT_DOUBLE_EQ(brick[4].origin.x, 0.125);  // odd rows: half a cell along
  const auto hex = ddm_layout_cells(DdmLayout::hex, {3, 3}, 1);
  ASSERT_EQ(hex.size(), 3u + 2u + 3u);
  const double h = hex[0].size.y;
  EXPECT_DOUBLE_EQ(h, 1.0 / 2.5);
  EXPECT_DOUBLE_EQ(hex[3].origin.y, 0.75 * h);       // rows interlock by a quarter cell
  EXPECT_NEAR(hex.back().origin.y + h, 1.0, 1e-15);  // the last row ends on the chart's edge
  try {
    ddm_layout_cells(DdmLayout::rect, {0, 3}, 1);
    FAIL() << "a zero-size layout must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("counts:", 0), 0u) << e.what();
  }
  EXPECT_THROW(ddm_layout_cells(DdmLayout::hex, {1, 3}, 1), std::invalid_argument);
}

// On a flat unit patch with height 1, T is the identity: the tile is reproduced exactly (seed: T is rigid there).
TEST(DdmEvaluate, TileOnAPlaneIsReproducedExactly) {
  const DdmSplineBase base({flat_patch(1.0, 1.0)});
  for (const char* kind : {"thorn", "chain", "hex"}) {
    const DdmTile tile = make_ddm_tile(kind);
    const TriMesh out = ddm_evaluate(base, tile, {DdmInstance{}}, 1.0);
    ASSERT_EQ(out.vertex_count(), tile.mesh.vertex_count());
    EXPECT_EQ(out.triangles, tile.mesh.triangles);
    for (std::size_t v = 0; v < out.vertex_count(); ++v) {
      EXPECT_NEAR(glm::length(out.positions[v] - tile.mesh.positions[v]), 0.0, 1e-14) << kind << " " << v;
      EXPECT_NEAR(glm::length(out.normals[v] - tile.mesh.normals[v]), 0.0, 1e-14) << kind << " " << v;
    }
  }
  // A 3 × 2 plane with 3 × 2 cells and height 0.5: every instance is the tile moved to its cell, w halved.
  const DdmSplineBase wide({flat_patch(3.0, 2.0)});
  const DdmTile thorn = make_ddm_tile("thorn");
  const auto cells = ddm_layout_cells(DdmLayout::rect, {3, 2}, 1);
  const TriMesh out = ddm_evaluate(wide, thorn, cells, 0.5);
  ASSERT_EQ(out.vertex_count(), 6 * thorn.mesh.vertex_count());
  const std::size_t nv = thorn.mesh.vertex_count();
  for (std::size_t k = 0; k < cells.size(); ++k)
    for (std::size_t v = 0; v < nv; v += 37) {
      const glm::dvec3 t = thorn.mesh.positions[v];
      const glm::dvec3 want(3.0 * cells[k].origin.x + t.x, 2.0 * cells[k].origin.y + t.y, 0.5 * t.z);
      EXPECT_NEAR(glm::length(out.positions[k * nv + v] - want), 0.0, 1e-13);
    }
}

// On a curved patch: T(x, y, 0) = S(u, v), the offset along n is exactly w·height, and the mapped normals are
// perpendicular to the mapped tile's edges (finite differences of T along the tile's tangent directions).
TEST(DdmEvaluate, CurvedBaseOffsetsAlongTheNormalWithExactNormals) {
  const DdmSplineBase base({bump_patch()});
  const DdmTile hex = make_ddm_tile("hex");
  const DdmInstance cell{0, {0.3, 0.2}, {0.4, 0.5}};
  const double height = 0.3;
  const TriMesh out = ddm_evaluate(base, hex, {cell}, height);
  for (std::size_t v = 0; v < out.vertex_count(); ++v) {
    const glm::dvec3 t = hex.mesh.positions[v];
    const DdmSurfacePoint s = base.eval(0, cell.origin.x + cell.size.x * t.x, cell.origin.y + cell.size.y * t.y);
    EXPECT_NEAR(glm::length(out.positions[v] - s.p), t.z * height, 1e-12);
    EXPECT_NEAR(glm::length(glm::cross(out.positions[v] - s.p, s.n)), 0.0, 1e-12);
  }
  // Normals: the hex tile's vertex normals are its flat faces' normals, so on a small cell (T nearly affine over a
  // face) each mapped face's geometric normal must agree with the mapped normals of its vertices.
  const TriMesh small = ddm_evaluate(base, hex, {DdmInstance{0, {0.45, 0.45}, {0.04, 0.05}}}, 0.02);
  double worst = 1.0;
  for (const glm::uvec3& f : small.triangles) {
    const glm::dvec3 fn = glm::normalize(
        glm::cross(small.positions[f.y] - small.positions[f.x], small.positions[f.z] - small.positions[f.x]));
    for (unsigned v : {f.x, f.y, f.z}) worst = std::min(worst, glm::dot(fn, small.normals[v]));
  }
  EXPECT_GT(worst, 0.999) << "mapped normals are the mapped faces' normals (exact cofactor map, no flips)";
  // Weingarten derivatives against central differences of n.
  const double h = 1e-6;
  for (double u : {0.2, 0.5, 0.8})
    for (double v : {0.3, 0.6}) {
      const DdmSurfacePoint s = base.eval(0, u, v);
      const glm::dvec3 fd_u = (base.eval(0, u + h, v).n - base.eval(0, u - h, v).n) / (2 * h);
      const glm::dvec3 fd_v = (base.eval(0, u, v + h).n - base.eval(0, u, v - h).n) / (2 * h);
      EXPECT_NEAR(glm::length(s.dn_du - fd_u), 0.0, 1e-6);
      EXPECT_NEAR(glm::length(s.dn_dv - fd_v), 0.0, 1e-6);
    }
}

TEST(DdmEvaluate, MetamorphosisEndsAreTheTilesAndBadInputIsRejected) {
  const DdmTile thorn = make_ddm_tile("thorn"), flower = make_ddm_tile("flower");
  const DdmTile a = ddm_morph(thorn, flower, 0.0), b = ddm_morph(thorn, flower, 1.0);
  EXPECT_EQ(a.mesh.positions, thorn.mesh.positions);
  EXPECT_EQ(b.mesh.positions, flower.mesh.positions);
  const DdmTile mid = ddm_morph(thorn, flower, 0.5);
  EXPECT_EQ(mid.mesh.triangles, thorn.mesh.triangles);
  EXPECT_NEAR(glm::length(mid.mesh.positions[10] - 0.5 * (thorn.mesh.positions[10] + flower.mesh.positions[10])), 0.0,
              1e-15);
  for (const glm::dvec3& n : ddm_morph(thorn, flower, 1.7).mesh.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
  EXPECT_THROW(ddm_morph(thorn, make_ddm_tile("chain"), 0.5), std::invalid_argument);
  EXPECT_THROW(ddm_morph(thorn, flower, std::nan("")), std::invalid_argument);

  const DdmSplineBase base({flat_patch(1.0, 1.0)});
  EXPECT_THROW(ddm_evaluate(base, thorn, {DdmInstance{}}, 0.0), std::invalid_argument);
  EXPECT_THROW(ddm_evaluate(base, thorn, {DdmInstance{3, {0, 0}, {1, 1}}}, 1.0), std::invalid_argument);
  EXPECT_THROW(DdmSplineBase({}), std::invalid_argument);
  EXPECT_THROW(base.eval(1, 0.5, 0.5), std::out_of_range);
}

// The teapot body's charts are the patches make_primitive("teapot") tessellates: their corners are teapot
// vertices, and their normals point out of the body (away from the y axis).
TEST(DdmBase, TeapotBodyChartsLieOnTheTeapot) {
  const DdmSplineBase body(teapot_body_patches());
  ASSERT_EQ(body.chart_count(), 8);
  const TriMesh teapot = make_primitive(PrimitiveKind::Teapot);
  for (int c = 0; c < body.chart_count(); ++c)
    for (const glm::dvec2 uv : {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
      const glm::dvec3 p = body.eval(c, uv.x, uv.y).p;
      double nearest = 1e300;
      for (const glm::dvec3& q : teapot.positions) nearest = std::min(nearest, glm::length(p - q));
      EXPECT_LT(nearest, 1e-9) << "chart " << c;
    }
  for (int c = 0; c < body.chart_count(); ++c) {
    const DdmSurfacePoint s = body.eval(c, 0.5, 0.5);
    EXPECT_GT(glm::dot(s.n, glm::normalize(glm::dvec3(s.p.x, 0.0, s.p.z))), 0.5) << "chart " << c;
  }
}

// Polygonal base (Loop limit surface via OpenSubdiv Bfr): neighbouring faces' charts meet on the same limit curve
// (no cracks across face borders), charts inside one face meet too, and a tile on a sphere lands at R + w·height.
TEST(DdmSubdivBase, ChartsMeetAcrossFaceBordersWithoutCracks) {
  const TriMesh sphere = make_primitive(PrimitiveKind::Sphere);
  const DdmSubdivBase base(sphere);
  ASSERT_EQ(base.chart_count(), int(3 * sphere.triangle_count()));
  // Edge (a, b) → (face, corner of a) for the face where it runs a → b.
  std::map<std::pair<unsigned, unsigned>, std::pair<int, int>> half;
  for (std::size_t f = 0; f < sphere.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) half[{sphere.triangles[f][k], sphere.triangles[f][(k + 1) % 3]}] = {int(f), k};
  double worst = 0.0;
  int shared = 0;
  for (const auto& [edge, fk] : half) {
    auto twin = half.find({edge.second, edge.first});
    if (twin == half.end()) continue;
    ++shared;
    // In f the edge a→b is chart (f, k)'s u-edge from a; in g it runs b→a, so a is g's corner j+1 and the edge is
    // that chart's v-edge from a.
    const int f = fk.first, k = fk.second, g = twin->second.first, j = (twin->second.second + 1) % 3;
    for (double l : {0.0, 0.3, 0.7, 1.0}) {
      const glm::dvec3 p = base.eval(3 * f + k, l, 0.0).p, q = base.eval(3 * g + j, 0.0, l).p;
      worst = std::max(worst, glm::length(p - q));
    }
    if (shared > 400) break;
  }
  EXPECT_GT(shared, 400);
  EXPECT_LT(worst, 1e-12);
  // Inside a face: chart k's v = 1 edge (B → C) is chart k+1's u = 1 edge (D' → C) reversed … both reach the centre.
  for (int f : {0, 17, 101}) {
    const glm::dvec3 c0 = base.eval(3 * f, 1.0, 1.0).p, c1 = base.eval(3 * f + 1, 1.0, 1.0).p;
    EXPECT_LT(glm::length(c0 - c1), 1e-12);
    EXPECT_LT(glm::length(base.eval(3 * f, 1.0, 0.4).p - base.eval(3 * f + 1, 0.4, 1.0).p), 1e-12);
  }
  // The thorn on a unit sphere: every vertex at its limit point + w·height along the limit normal; the limit surface
  // of the tessellated sphere lies within 1 % of R.
  const DdmTile thorn = make_ddm_tile("thorn");
  const std::vector<DdmInstance> cells = {{5, {0.1, 0.1}, {0.8, 0.8}}, {200, {0.0, 0.0}, {1.0, 1.0}}};
  const TriMesh out = ddm_evaluate(base, thorn, cells, 0.1);
  for (std::size_t k = 0; k < cells.size(); ++k)
    for (std::size_t v = 0; v < thorn.mesh.vertex_count(); ++v) {
      const glm::dvec3 t = thorn.mesh.positions[v];
      const glm::dvec3 x = out.positions[k * thorn.mesh.vertex_count() + v];
      EXPECT_NEAR(glm::length(x), 1.0 + 0.1 * t.z, 0.01);
    }
}

TEST(DdmSubdivBase, BadMeshesAreRejected) {
  EXPECT_THROW(DdmSubdivBase(TriMesh{}), std::invalid_argument);
  TriMesh bad = make_primitive(PrimitiveKind::Sphere);
  bad.positions[2].x = std::nan("");
  EXPECT_THROW({ DdmSubdivBase b(bad); }, std::invalid_argument);
  TriMesh fin;  // three triangles on one edge (a non-manifold fan)
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  try {
    DdmSubdivBase b(fin);
    FAIL() << "a non-manifold base must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("base:", 0), 0u) << e.what();
  }
  TriMesh out_of_range = make_primitive(PrimitiveKind::Sphere);
  out_of_range.triangles[0].x = 1u << 30;
  EXPECT_THROW({ DdmSubdivBase b(out_of_range); }, std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
