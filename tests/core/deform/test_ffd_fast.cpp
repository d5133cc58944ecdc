// Fast float FFD against the double reference; subdivision and the benchmark function (smoke).
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <numbers>
#include <sstream>

#include "core/deform/ffd_bench.h"
#include "core/deform/ffd_fast.h"
#include "core/mesh/mesh_io.h"
#include "deform_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

struct Errors {
  double position = 0, normal_angle = 0;
};

Errors compare_fast(const TrivariateBSpline<glm::dvec3>& F, const Embedding& e, const TriMesh& mesh) {
  const auto params = embed_points(e, mesh.positions);
  std::vector<glm::dvec3> rp, rn;
  ffd_evaluate(F, e, params, mesh.normals, rp, rn);
  const FfdFastLattice fast(F, e);
  FloatSoA3 fp, fn, fp_only;
  ffd_evaluate_fast(fast, FloatSoA3::from(params), FloatSoA3::from(mesh.normals), fp, fn);
  ffd_evaluate_fast(fast, FloatSoA3::from(params), fp_only);
  Errors err;
  for (std::size_t i = 0; i < rp.size(); ++i) {
    err.position = std::max(err.position, glm::length(rp[i] - glm::dvec3(fp.x[i], fp.y[i], fp.z[i])));
    err.position = std::max(err.position, glm::length(rp[i] - glm::dvec3(fp_only.x[i], fp_only.y[i], fp_only.z[i])));
    const glm::dvec3 f(fn.x[i], fn.y[i], fn.z[i]);  // angle by atan2: acos loses precision near 0
    err.normal_angle = std::max(err.normal_angle, std::atan2(glm::length(glm::cross(rn[i], f)), glm::dot(rn[i], f)));
    EXPECT_NEAR(glm::length(f), 1.0, 1e-6);
  }
  Aabb lb;
  for (const auto& p : F.control_points()) lb.extend(p);
  err.position /= lb.diagonal();
  return err;
}

}  // namespace

TEST(FfdFast, MatchesReferenceForAllKernelOrders) {
  TriMesh sphere = make_uv_sphere(1.0, 30, 60);
  sphere.positions.push_back({0.0, 0.0, 0.0});  // a vertex at a knot-aligned interior point
  sphere.normals.push_back({0.0, 1.0, 0.0});
  const Embedding e = embed_bounding_box(sphere.positions, {0, 1});
  for (int ou = 2; ou <= 4; ++ou)
    for (int ov = 2; ov <= 4; ++ov)
      for (int ow = 2; ow <= 4; ++ow) {
        const auto F = bent_lattice(e, KnotVector::clamped_uniform(ou, 6), KnotVector::clamped_uniform(ov, 5),
                                    KnotVector::clamped_uniform(ow, 4));
        ASSERT_TRUE(FfdFastLattice(F, e).has_kernel());
        const Errors err = compare_fast(F, e, sphere);
        EXPECT_LE(err.position, 1e-5) << ou << ov << ow;
        EXPECT_LE(err.normal_angle, 1e-5) << ou << ov << ow;
      }
}

TEST(FfdFast, NonUniformKnotsAndFallbackOrders) {
  TriMesh sphere = make_uv_sphere(2.0, 20, 40);
  for (auto& p : sphere.positions) p += glm::dvec3(100.0, -50.0, 30.0);  // far from the origin
  const Embedding e = embed_bounding_box(sphere.positions, {2, 0});
  const KnotVector nonuni(3, {0, 0, 0, 0.1, 0.15, 0.6, 1, 1, 1});
  auto F = bent_lattice(e, nonuni, KnotVector::clamped_uniform(4, 7), KnotVector::clamped_uniform(2, 3));
  EXPECT_LE(compare_fast(F, e, sphere).position, 1e-5);
  auto G = bent_lattice(e, KnotVector::clamped_uniform(5, 6), KnotVector::clamped_uniform(3, 4),
                        KnotVector::clamped_uniform(2, 2));
  EXPECT_FALSE(FfdFastLattice(G, e).has_kernel());
  EXPECT_LE(compare_fast(G, e, sphere).position, 1e-6);
}

TEST(FfdFast, ThreadCountDoesNotChangeResults) {
  TriMesh sphere = make_uv_sphere(1.0, 60, 120);
  const Embedding e = embed_bounding_box(sphere.positions, {0, 1});
  const auto F = bent_lattice(e, KnotVector::clamped_uniform(4, 4), KnotVector::clamped_uniform(4, 4),
                              KnotVector::clamped_uniform(4, 4));
  const FfdFastLattice fast(F, e);
  const FloatSoA3 params = FloatSoA3::from(embed_points(e, sphere.positions));
  const FloatSoA3 normals = FloatSoA3::from(sphere.normals);
  FloatSoA3 p1, n1, pn, nn;
  tbb::task_arena(8).execute([&] { ffd_evaluate_fast(fast, params, normals, pn, nn); });
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    ffd_evaluate_fast(fast, params, normals, p1, n1);
  }
  EXPECT_EQ(p1.x, pn.x);
  EXPECT_EQ(p1.y, pn.y);
  EXPECT_EQ(p1.z, pn.z);
  EXPECT_EQ(n1.x, nn.x);
}

TEST(FfdFast, SizeMismatchThrows) {
  const Embedding e = embed_bounding_box({{0, 0, 0}, {1, 1, 1}}, {0, 1});
  const auto F = identity_lattice(e, KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                                  KnotVector::clamped_uniform(2, 2));
  const FfdFastLattice fast(F, e);
  FloatSoA3 params = FloatSoA3::from({{0.5, 0.5, 0.5}, {0.1, 0.2, 0.3}}), normals = FloatSoA3::from({{0, 1, 0}});
  FloatSoA3 p, n;
  EXPECT_THROW(ffd_evaluate_fast(fast, params, normals, p, n), std::invalid_argument);
}

TEST(Subdivision, BilinearLevelOneCountsAndPlanarity) {
  TriMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};
  const TriMesh s = subdivide_bilinear(quad, 1);
  EXPECT_EQ(s.positions.size(), 4u + 5u + 2u);  // V + E + F
  EXPECT_EQ(s.triangles.size(), 2u * 3u * 2u);  // each triangle → 3 quads → 6 triangles
  for (const auto& p : s.positions) EXPECT_DOUBLE_EQ(p.y, 0.0);
  EXPECT_EQ(subdivide_bilinear(quad, 0).positions.size(), 4u);
  TriMesh sphere = make_uv_sphere(1.0, 8, 16);
  EXPECT_GT(signed_volume(subdivide_bilinear(sphere, 2)), 0.0);  // winding kept
}

TEST(Benchmark, SmokeRunWithFallbackMesh) {
  FfdBenchOptions o;
  o.mesh_path = "/nonexistent/bunny.obj";
  o.subdivision_level = 0;
  o.runs = 1;
  const nlohmann::json r = run_ffd_benchmark(o);
  EXPECT_TRUE(r.at("mesh").at("fallback").get<bool>());
  EXPECT_GT(r.at("mesh").at("vertices").get<int>(), 30000);
  EXPECT_EQ(r.at("results").size(), 2u * 2u * 2u * 2u);  // orders × outputs × thread counts × paths
  for (const auto& a : r.at("accuracy")) EXPECT_LE(a.at("relative_position_error").get<double>(), 1e-5);
  std::ostringstream os;
  print_ffd_benchmark(r, os);
  EXPECT_NE(os.str().find("not found"), std::string::npos);
  o.orders = {5};
  EXPECT_THROW(run_ffd_benchmark(o), std::invalid_argument);
}
