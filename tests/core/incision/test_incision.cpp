// Incisions (core/incision/incision.h, seed §6.4): frame fitting from a stroke, the local lattice of Eq. 6.2 with its
// opening, the mesh split along the cut sheet and the cut-depth walls. Topology is checked with OpenMesh and a plain
// edge count: 2-manifold, no duplicate faces, no boundary with walls, one new boundary loop per incision without.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"
#include "incision_test_util.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

using test::frame_through;
using test::segment;
using test::topology;

// A camera looking straight down at the xz-plane.
Camera top_camera() { return trispline::test::top_camera(3.0, 45, {800, 800}); }

// The 2 × 2 plane (y = 0) with 64 × 64 quads, and an incision along x from −0.5 to 0.5 at z = 0.013.
struct PlaneCut {
  TriMesh plane = make_plane(64);
  IncisionFrame frame = *frame_through(plane, top_camera(), segment({-0.5, 0.0, 0.013}, {0.5, 0.0, 0.013}, 12));
  IncisionParams params;
  PlaneCut() {
    params.width = 0.2;
    params.depth = 0.1;
    params.opening = 0.05;
  }
};

TEST(Incision, FrameFollowsTheStroke) {
  PlaneCut pc;
  EXPECT_EQ(pc.frame.hits.size(), 12u);
  for (const glm::dvec3& h : pc.frame.hits) EXPECT_NEAR(h.y, 0.0, 1e-9);
  EXPECT_NEAR(pc.frame.generator.eval(0.0).x, -0.5, 1e-3);
  EXPECT_NEAR(pc.frame.generator.eval(1.0).x, 0.5, 1e-3);
  EXPECT_NEAR(pc.frame.generator.eval(0.5).z, 0.013, 1e-3);
  const glm::dvec3 n = glm::normalize(pc.frame.normal.eval(0.5));
  EXPECT_NEAR(n.y, 1.0, 1e-9);  // the plane's normal, facing the camera
  // The un-opened lattice straddles the surface: ±width across, from above the surface to below the depth.
  const TrivariateBSpline<glm::dvec3> F = incision_lattice(pc.frame, pc.params);
  EXPECT_EQ(F.control_counts(), glm::ivec3(7, 4, 5));  // l = 7, m = clamp(12/3, order, 24), n = 5
}

TEST(Incision, PlaneWithWallsIsClosedAlongTheCut) {
  PlaneCut pc;
  const IncisionResult r = incise(pc.plane, pc.frame, pc.params);
  const test::Topology before = topology(pc.plane), after = topology(r.mesh);
  EXPECT_GT(r.cut_edges, 20u);
  EXPECT_EQ(r.tips, 2u);                      // the stroke ends inside the plane: the rims meet twice
  EXPECT_EQ(r.split_faces, r.cut_edges + 1);  // one slit: a chain of cut edges between two tip faces
  EXPECT_EQ(r.wall_faces, 4u * pc.params.wall_rows * r.split_faces);
  EXPECT_EQ(r.newton_fallbacks, 0u);
  EXPECT_TRUE(is_manifold(after));
  EXPECT_EQ(after.boundary_edges, before.boundary_edges);  // only the plane's own border
  EXPECT_EQ(after.boundary_loops, 1u);
  // Walls: inside material, down to the depth (the bottom curve is at y = −depth below the straight generator).
  ASSERT_EQ(r.mesh.face_material.size(), r.mesh.triangles.size());
  std::size_t inside = 0;
  double lowest = 0.0;
  for (std::size_t f = 0; f < r.mesh.triangles.size(); ++f) {
    if (r.mesh.face_material[f] != kMaterialInside) continue;
    ++inside;
    for (int c = 0; c < 3; ++c) lowest = std::min(lowest, r.mesh.positions[r.mesh.triangles[f][c]].y);
  }
  EXPECT_EQ(inside, r.wall_faces);
  EXPECT_NEAR(lowest, -pc.params.depth, 1e-6);
  // The surface opens by `opening` at mid-stroke: no surface vertex inside the gap near x = 0, rims at ±opening/2.
  double minus_rim = -1e9, plus_rim = 1e9;
  for (std::size_t f = 0; f < r.mesh.triangles.size(); ++f) {
    if (r.mesh.face_material[f] != kMaterialSurface) continue;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3& p = r.mesh.positions[r.mesh.triangles[f][c]];
      if (std::abs(p.x) > 0.03 || std::abs(p.z - 0.013) > 0.2) continue;
      if (p.z < 0.013)
        minus_rim = std::max(minus_rim, p.z - 0.013);
      else
        plus_rim = std::min(plus_rim, p.z - 0.013);
    }
  }
  EXPECT_NEAR(plus_rim - minus_rim, pc.params.opening, 0.1 * pc.params.opening) << minus_rim << " " << plus_rim;
  // Vertices outside the lattice keep their positions bit for bit; input vertices keep their indices.
  for (std::size_t v = 0; v < pc.plane.positions.size(); ++v) {
    const glm::dvec3& p = pc.plane.positions[v];
    if (std::abs(p.x) > 0.75 || std::abs(p.z) > 0.3) {
      EXPECT_EQ(std::memcmp(&p, &r.mesh.positions[v], sizeof p), 0) << v;
    }
  }
}

TEST(Incision, PlaneWithoutWallsHasOneNewBoundaryLoop) {
  PlaneCut pc;
  pc.params.walls = false;
  const IncisionResult r = incise(pc.plane, pc.frame, pc.params);
  const test::Topology after = topology(r.mesh);
  EXPECT_EQ(r.wall_faces, 0u);
  EXPECT_TRUE(is_manifold(after));
  EXPECT_EQ(after.boundary_loops, 2u);  // the plane's border and the incision
  // Each split face leaves one rim edge on each side of the slit.
  EXPECT_EQ(after.boundary_edges, topology(pc.plane).boundary_edges + 2 * r.split_faces);
}

TEST(Incision, CrossingIncisionsCompose) {
  PlaneCut pc;
  const IncisionResult first = incise(pc.plane, pc.frame, pc.params);
  // The second stroke crosses the first cut (and its walls) at right angles.
  const auto f2 = frame_through(first.mesh, top_camera(), segment({0.107, 0.0, -0.4}, {0.107, 0.0, 0.4}, 12));
  ASSERT_TRUE(f2.has_value());
  const IncisionResult second = incise(first.mesh, *f2, pc.params);
  EXPECT_GT(second.cut_edges, first.cut_edges / 2);
  const test::Topology t = topology(second.mesh);
  EXPECT_TRUE(is_manifold(t));
  EXPECT_EQ(t.boundary_edges, topology(pc.plane).boundary_edges);
  EXPECT_EQ(t.boundary_loops, 1u);
}

TEST(Incision, DeterministicAndZeroOpeningKeepsTheSurfaceInPlace) {
  PlaneCut pc;
  const IncisionResult a = incise(pc.plane, pc.frame, pc.params), b = incise(pc.plane, pc.frame, pc.params);
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
  EXPECT_EQ(std::memcmp(a.mesh.positions.data(), b.mesh.positions.data(), a.mesh.positions.size() * 24), 0);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  pc.params.opening = 0.0;
  const IncisionResult c = incise(pc.plane, pc.frame, pc.params);
  for (std::size_t v = 0; v < pc.plane.positions.size(); ++v) EXPECT_EQ(c.mesh.positions[v], pc.plane.positions[v]);
  EXPECT_EQ(topology(c.mesh).boundary_edges, topology(pc.plane).boundary_edges);
}

TEST(Incision, BadParametersAreRejected) {
  PlaneCut pc;
  auto fails_with = [&](IncisionParams p, const char* field) {
    try {
      incise(pc.plane, pc.frame, p);
      ADD_FAILURE() << "no error for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string(field) + ":", 0), 0u) << e.what();
    }
  };
  IncisionParams p = pc.params;
  p.depth = 0.0;
  fails_with(p, "depth");
  p = pc.params, p.width = -1.0;
  fails_with(p, "width");
  p = pc.params, p.opening = -0.1;
  fails_with(p, "opening");
  p = pc.params, p.opening = 5.0;  // folds the lattice over (seed Theorem 6)
  fails_with(p, "opening");
  p = pc.params, p.order = 5;
  fails_with(p, "order");
  p = pc.params, p.controls_u = 6;
  fails_with(p, "controls");
  // A stroke that misses the plane gives no frame.
  RayCaster rc;
  rc.add_mesh(pc.plane);
  rc.commit();
  EXPECT_FALSE(fit_incision_frame({{5, 5}, {40, 8}}, top_camera(), rc).has_value());
  EXPECT_FALSE(fit_incision_frame({{400, 400}}, top_camera(), rc).has_value());
}

// A camera on +z looking at the origin.
Camera front_camera(double dist = 4.0) { return trispline::test::front_camera(dist, 40, {800, 600}); }

TEST(Incision, StrokeCasterHitsLikeTheWholeMesh) {
  const TriMesh sphere = make_sphere(64, 32);
  std::vector<glm::dvec2> px;
  for (int i = 0; i < 40; ++i) px.emplace_back(250.0 + 7.3 * i, 200.0 + 3.1 * i + 20.0 * std::sin(i * 0.7));
  RayCaster full;
  full.add_mesh(sphere);
  full.commit();
  const RayCaster sub = stroke_ray_caster(sphere, front_camera(), px, BuildQuality::high);
  int hits = 0;
  for (const glm::dvec2& p : px) {
    const auto a = full.intersect(front_camera().eye, front_camera().ray_direction(p));
    const auto b = sub.intersect(front_camera().eye, front_camera().ray_direction(p));
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    ++hits;
    EXPECT_EQ(a->t, b->t);
    EXPECT_EQ(a->position, b->position);
  }
  EXPECT_GT(hits, 20);
}

TEST(Incision, SphereStaysClosedWithWallsAndOpensWithout) {
  const TriMesh sphere = make_sphere(64, 32);
  const auto f = frame_through(sphere, front_camera(), segment({-0.4, 0.1, 0.9}, {0.35, -0.15, 0.9}, 20));
  ASSERT_TRUE(f.has_value());
  for (const glm::dvec3& h : f->hits) EXPECT_NEAR(glm::length(h), 1.0, 0.01);
  IncisionParams p;
  p.width = 0.12, p.depth = 0.08, p.opening = 0.04;
  for (IncisionKernel k : {IncisionKernel::gaussian, IncisionKernel::bspline}) {
    p.kernel = k;
    p.walls = true;
    const IncisionResult r = incise(sphere, *f, p);
    const test::Topology t = topology(r.mesh);
    EXPECT_EQ(t.boundary_edges, 0u);
    EXPECT_TRUE(is_manifold(t));
    EXPECT_EQ(r.tips, 2u);
    EXPECT_EQ(r.wall_faces, 4u * p.wall_rows * r.split_faces);
    // The walls stay under the surface: inside the unit sphere, no deeper than depth (plus the chord sag).
    for (std::size_t v = sphere.positions.size(); v < r.mesh.positions.size(); ++v) {
      EXPECT_LT(glm::length(r.mesh.positions[v]), 1.0 + 1e-3);
      EXPECT_GT(glm::length(r.mesh.positions[v]), 1.0 - p.depth - 0.02);
    }
    p.walls = false;
    const IncisionResult o = incise(sphere, *f, p);
    const test::Topology to = topology(o.mesh);
    EXPECT_EQ(to.boundary_loops, 1u);
    EXPECT_EQ(to.nonmanifold_edges, 0u);
    EXPECT_EQ(to.openmesh_rejected, 0u);
  }
}

#ifdef TRISPLINE_HAVE_VENUS
// The Venus bust (scale 0.01) seen from the front; strokes on the cheeks and across the nose (seed Fig. 6.8).
Camera venus_camera() {
  Camera c;
  c.eye = {-0.14, 1.35, 1.5};
  c.target = {-0.14, 1.33, 0.0};
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = 20;
  c.viewport = {800, 600};
  return c;
}

TEST(Incision, VenusThreeIncisionsComposeAndStayManifold) {
  Transform tr;
  tr.scale = glm::dvec3(0.01);
  TriMesh m = transformed(load_mesh(TRISPLINE_SOURCE_DIR "/assets/data/venus.obj"), tr);
  const test::Topology input = topology(m);
  const std::vector<std::vector<glm::dvec3>> strokes = {
      segment({-0.26, 1.35, 0.08}, {-0.20, 1.22, 0.08}, 12),   // cheek
      segment({-0.04, 1.34, 0.1}, {-0.08, 1.22, 0.1}, 12),     // other cheek
      segment({-0.21, 1.37, 0.15}, {-0.07, 1.37, 0.15}, 12)};  // across the nose
  std::size_t walls = 0;
  for (const auto& s : strokes) {
    const auto f = frame_through(m, venus_camera(), s);
    ASSERT_TRUE(f.has_value());
    IncisionParams p;
    p.width = 0.03, p.depth = 0.02, p.opening = 0.01;
    const IncisionResult r = incise(m, *f, p);
    EXPECT_GT(r.cut_edges, 1u);
    EXPECT_EQ(r.wall_faces, 4u * p.wall_rows * r.split_faces);
    walls += r.wall_faces;
    const test::Topology t = topology(r.mesh);
    EXPECT_EQ(t.nonmanifold_edges, input.nonmanifold_edges);  // no new non-manifold edge
    EXPECT_EQ(t.boundary_edges, input.boundary_edges);        // the walls close every cut
    EXPECT_EQ(t.boundary_loops, input.boundary_loops);
    EXPECT_EQ(t.duplicate_faces, 0u);
    EXPECT_EQ(t.repeated_halfedges, 0u);
    EXPECT_EQ(t.openmesh_rejected, input.openmesh_rejected);
    m = r.mesh;
  }
  std::size_t inside = 0;
  for (MaterialSlot mat : m.face_material) inside += mat == kMaterialInside;
  EXPECT_EQ(inside, walls);
}
#endif

#ifdef TRISPLINE_HAVE_BUNNY
TEST(Incision, BunnyCutKeepsItsTopology) {
  const TriMesh bunny = load_mesh(TRISPLINE_SOURCE_DIR "/assets/data/bunny.obj");
  const test::Topology input = topology(bunny);
  const auto f = frame_through(bunny, front_camera(5.0), segment({-0.4, 0.0, 0.0}, {0.4, 0.1, 0.0}, 24));
  ASSERT_TRUE(f.has_value());
  EXPECT_GE(f->hits.size(), 20u);
  IncisionParams p;
  p.width = 0.08, p.depth = 0.05, p.opening = 0.03;
  for (bool walls : {true, false}) {
    p.walls = walls;
    const IncisionResult r = incise(bunny, *f, p);
    EXPECT_GT(r.cut_edges, 50u);
    EXPECT_GT(r.embedded_vertices, 200u);
    EXPECT_EQ(r.wall_faces, walls ? 4u * p.wall_rows * r.split_faces : 0u);
    const test::Topology t = topology(r.mesh);
    EXPECT_EQ(t.nonmanifold_edges, input.nonmanifold_edges);
    EXPECT_EQ(t.duplicate_faces, 0u);
    EXPECT_EQ(t.repeated_halfedges, 0u);
    EXPECT_EQ(t.openmesh_rejected, input.openmesh_rejected);
    EXPECT_EQ(t.boundary_loops, input.boundary_loops + (walls ? 0u : r.tips / 2));
    if (walls) {
      EXPECT_EQ(t.boundary_edges, input.boundary_edges);
    }
  }
}
#endif

// Performance figure for docs (printed, not asserted): a ~100K-vertex sphere.
TEST(Incision, DenseSphereStaysManifold) {
  const TriMesh sphere = make_sphere(448, 224);
  ASSERT_GT(sphere.positions.size(), 99000u);
  const auto f = frame_through(sphere, front_camera(), segment({-0.4, 0.1, 0.9}, {0.35, -0.15, 0.9}, 30));
  ASSERT_TRUE(f.has_value());
  IncisionParams p;
  p.width = 0.1, p.depth = 0.06, p.opening = 0.03;
  IncisionResult r = incise(sphere, *f, p);  // warm-up
  auto cpu_ms = [] {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
  };
  double best = 1e9, best_cpu = 1e9, best_total = 1e9;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_ms();
    r = incise(sphere, *f, p);
    best_cpu = std::min(best_cpu, cpu_ms() - c0);
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    // What incision.draw adds: the BVH over the object and the frame fit.
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<glm::dvec2> px;
    for (const glm::dvec3& q : segment({-0.4, 0.1, 0.9}, {0.35, -0.15, 0.9}, 30)) {
      const glm::dvec3 pp = front_camera().project(q);
      px.emplace_back(pp.x, pp.y);
    }
    const RayCaster rc = stroke_ray_caster(sphere, front_camera(), px, BuildQuality::high);
    const auto f2 = fit_incision_frame(px, front_camera(), rc);
    ASSERT_TRUE(f2.has_value());
    best_total =
        std::min(best_total, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count());
  }
  std::printf(
      "incise: %zu vertices, %zu cut edges, %zu embedded: %.2f ms wall, %.2f ms CPU (best of 5); "
      "BVH + frame fit: %.2f ms\n",
      sphere.positions.size(), r.cut_edges, r.embedded_vertices, best, best_cpu, best_total);
  const test::Topology t = topology(r.mesh);
  EXPECT_EQ(t.boundary_edges, 0u);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.openmesh_rejected, 0u);
  EXPECT_GT(r.cut_edges, 100u);
}

}  // namespace
}  // namespace trispline::core
