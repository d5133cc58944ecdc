// Reference FFD: embedding, identity reproduction, exact normals vs finite differences, determinism, ffd_apply.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <glm/gtx/string_cast.hpp>
#include <random>

#include "core/ffd/ffd.h"
#include "core/mesh/mesh_io.h"
#include "ffd_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

TEST(Embedding, MapsBoundingBoxToUnitCubeWithPositiveDeterminant) {
  const std::vector<glm::dvec3> pts{{-1, 2, 3}, {4, 5, 7}, {0, 3, 5}};
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      if (a == c) continue;
      const Embedding e = embed_bounding_box(pts, {a, c});
      EXPECT_GT(glm::determinant(e.linear), 0.0) << "length " << a << " up " << c;
      const glm::dvec3 lo = e.apply({-1, 2, 3}), hi = e.apply({4, 5, 7});
      EXPECT_NEAR(lo.x, 0.0, 1e-15);  // length axis: min → u = 0
      EXPECT_NEAR(hi.x, 1.0, 1e-15);
      EXPECT_NEAR(lo.z, 0.0, 1e-15);  // up axis: bottom → w = 0
      EXPECT_NEAR(hi.z, 1.0, 1e-15);
      EXPECT_NEAR(std::abs(hi.y - lo.y), 1.0, 1e-15);
      // u follows exactly the length axis
      glm::dvec3 d(0.0);
      d[a] = 1.0;
      EXPECT_GT((e.apply(pts[0] + d) - e.apply(pts[0])).x, 0.0);
    }
}

TEST(Embedding, FlatExtentMapsToMiddleAndErrorsAreReported) {
  const std::vector<glm::dvec3> flat{{0, 1, 0}, {2, 1, 0}, {0, 1, 3}};
  const Embedding e = embed_bounding_box(flat, {0, 1});
  EXPECT_DOUBLE_EQ(e.apply({1, 1, 1}).z, 0.5);
  EXPECT_THROW(embed_bounding_box(flat, {1, 1}), std::invalid_argument);
  EXPECT_THROW(embed_bounding_box(flat, {0, 3}), std::invalid_argument);
  EXPECT_THROW(embed_bounding_box({}, {0, 1}), std::invalid_argument);
  EXPECT_THROW(embed_bounding_box({{0, NAN, 0}}, {0, 1}), std::invalid_argument);
}

TEST(Ffd, IdentityLatticeReproducesPoints) {
  const auto pts = random_points(2000, {-2, 0.5, 1}, {3, 1.5, 4}, 7);
  const Embedding e = embed_bounding_box(pts, {2, 1});
  const auto params = embed_points(e, pts);
  const double diag = bounds_of(pts).diagonal();
  for (int o : {2, 3, 4})
    for (int n : {o, o + 3}) {
      const auto F = identity_lattice(e, KnotVector::clamped_uniform(o, n), KnotVector::clamped_uniform(o, n + 1),
                                      KnotVector::clamped_uniform(std::max(2, o - 1), n));
      std::vector<glm::dvec3> out;
      ffd_evaluate(F, params, out);
      ASSERT_EQ(out.size(), pts.size());
      double err = 0;
      for (std::size_t i = 0; i < pts.size(); ++i) err = std::max(err, glm::length(out[i] - pts[i]));
      EXPECT_LE(err, 1e-12 * diag) << "order " << o << " controls " << n;
    }
}

TEST(Ffd, NormalsMatchFiniteDifferencesOfTheMapping) {
  TriMesh sphere = make_uv_sphere(0.8, 24, 48);
  // Embed a box larger than the sphere so central differences stay inside the parameter domain.
  const Embedding e = embed_bounding_box({{-1, -1, -1}, {1, 1, 1}}, {0, 1});
  const auto F = bent_lattice(e, KnotVector::clamped_uniform(4, 6), KnotVector::clamped_uniform(3, 5),
                              KnotVector::clamped_uniform(4, 5));
  const auto params = embed_points(e, sphere.positions);
  std::vector<glm::dvec3> pos, nrm;
  ffd_evaluate(F, e, params, sphere.normals, pos, nrm);
  const double h = 1e-5;
  double worst = 0;
  for (std::size_t i = 0; i < sphere.positions.size(); ++i) {
    const glm::dvec3 x = sphere.positions[i], n = sphere.normals[i];
    const glm::dvec3 t1 =
        glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 t2 = glm::cross(n, t1);  // t1 × t2 = n
    auto G = [&](const glm::dvec3& y) { return F.eval(e.apply(y)); };
    const glm::dvec3 d1 = (G(x + h * t1) - G(x - h * t1)) / (2 * h);
    const glm::dvec3 d2 = (G(x + h * t2) - G(x - h * t2)) / (2 * h);
    const glm::dvec3 fd = glm::normalize(glm::cross(d1, d2));
    worst = std::max(worst, glm::length(fd - nrm[i]));
    EXPECT_NEAR(glm::length(nrm[i]), 1.0, 1e-12);
    EXPECT_LE(glm::length(pos[i] - G(x)), 1e-12);
  }
  EXPECT_LE(worst, 1e-6);
}

TEST(Ffd, BitIdenticalForAnyThreadCount) {
  TriMesh sphere = make_uv_sphere(1.0, 60, 120);
  const Embedding e = embed_bounding_box(sphere.positions, {0, 1});
  const auto F = bent_lattice(e, KnotVector::clamped_uniform(4, 5), KnotVector::clamped_uniform(4, 5),
                              KnotVector::clamped_uniform(3, 4));
  const auto params = embed_points(e, sphere.positions);
  std::vector<glm::dvec3> p1, n1, pn, nn;
  tbb::task_arena arena(8);  // more threads than cores on purpose (oversubscribed arena)
  arena.execute([&] { ffd_evaluate(F, e, params, sphere.normals, pn, nn); });
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    ffd_evaluate(F, e, params, sphere.normals, p1, n1);
  }
  ASSERT_EQ(p1.size(), pn.size());
  EXPECT_EQ(std::memcmp(p1.data(), pn.data(), p1.size() * sizeof(glm::dvec3)), 0);
  EXPECT_EQ(std::memcmp(n1.data(), nn.data(), n1.size() * sizeof(glm::dvec3)), 0);
  std::vector<glm::dvec3> q1, qn;
  arena.execute([&] { ffd_evaluate(F, params, qn); });
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    ffd_evaluate(F, params, q1);
  }
  EXPECT_EQ(std::memcmp(q1.data(), qn.data(), q1.size() * sizeof(glm::dvec3)), 0);
  EXPECT_EQ(std::memcmp(q1.data(), p1.data(), q1.size() * sizeof(glm::dvec3)), 0);  // same positions either way
}

TEST(Ffd, ApplyDeformsMeshKeepsTopologyAndOrientation) {
  TriMesh sphere = make_uv_sphere(1.0, 16, 32);
  const double vol0 = signed_volume(sphere);
  ASSERT_GT(vol0, 0.0);
  const Embedding e = embed_bounding_box(sphere.positions, {0, 1});
  FfdBinding b{bent_lattice(e, KnotVector::clamped_uniform(3, 4), KnotVector::clamped_uniform(3, 4),
                            KnotVector::clamped_uniform(3, 4)),
               e, embed_points(e, sphere.positions)};
  const TriMesh out = ffd_apply(b, sphere);
  EXPECT_EQ(out.triangles, sphere.triangles);
  EXPECT_EQ(out.positions.size(), sphere.positions.size());
  EXPECT_EQ(out.normals.size(), sphere.positions.size());
  EXPECT_GT(signed_volume(out), 0.0);
  // Outward normals stay outward: they agree with the deformed face normals.
  TriMesh recomputed = out;
  compute_vertex_normals(recomputed);
  for (std::size_t i = 0; i < out.normals.size(); ++i) EXPECT_GT(glm::dot(out.normals[i], recomputed.normals[i]), 0.9);
  TriMesh no_normals = sphere;
  no_normals.normals.clear();
  EXPECT_EQ(ffd_apply(b, no_normals).normals.size(), sphere.positions.size());
  b.params.pop_back();
  EXPECT_THROW(ffd_apply(b, sphere), std::invalid_argument);
}

// ffd_evaluate picks a fixed-order evaluator (one order ≤ 4 on every axis, none periodic) with a span table instead
// of KnotVector::find_span, or the generic one. Both must agree with TrivariateBSpline::eval / eval_first at random
// points and exactly on every knot, including C⁻¹ knots (multiplicity = order): a wrong span there lands on the
// other side of a jump, far outside the tolerance.
TEST(Ffd, EveryEvaluatorPathMatchesTheSplineOnAndBetweenKnots) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto knots = [&](int order, int controls) {  // clamped, interior knots with multiplicities up to `order`
    std::vector<double> interior;
    while (static_cast<int>(interior.size()) < controls - order) {
      const double v = 0.05 + 0.9 * unit(rng);
      const int m = std::min<int>(1 + static_cast<int>(unit(rng) * order), controls - order - int(interior.size()));
      for (int i = 0; i < m; ++i) interior.push_back(v);
    }
    std::sort(interior.begin(), interior.end());
    std::vector<double> k(order, 0.0);
    k.insert(k.end(), interior.begin(), interior.end());
    k.insert(k.end(), order, 1.0);
    return KnotVector(order, k);
  };
  for (const glm::ivec3 orders : {glm::ivec3(2), glm::ivec3(3), glm::ivec3(4), glm::ivec3(3, 4, 2), glm::ivec3(5)}) {
    const KnotVector ku = knots(orders.x, 9), kv = knots(orders.y, 8), kw = knots(orders.z, 7);
    std::vector<glm::dvec3> cps(9 * 8 * 7);
    for (glm::dvec3& c : cps) c = {unit(rng), unit(rng), unit(rng)};
    const TrivariateBSpline<glm::dvec3> F(ku, kv, kw, cps);
    std::vector<glm::dvec3> params;
    for (int i = 0; i < 300; ++i) params.push_back({unit(rng), unit(rng), unit(rng)});
    for (double u : ku.knots()) params.push_back({u, unit(rng), unit(rng)});
    for (double v : kv.knots()) params.push_back({unit(rng), v, unit(rng)});
    for (double w : kw.knots()) params.push_back({unit(rng), unit(rng), w});
    params.push_back({-0.5, 1.5, 0.5});  // clamped to the domain
    std::vector<glm::dvec3> normals(params.size(), glm::normalize(glm::dvec3(0.3, -0.5, 0.8))), p, n, q;
    Embedding e;
    e.linear = glm::dmat3(1.0);
    ffd_evaluate(F, e, params, normals, p, n);
    ffd_evaluate(F, params, q);
    for (std::size_t i = 0; i < params.size(); ++i) {
      const auto d = F.eval_first(params[i]);
      EXPECT_LT(glm::length(p[i] - d.value), 1e-12) << glm::to_string(orders) << " at " << glm::to_string(params[i]);
      EXPECT_EQ(p[i], q[i]);
      const glm::dvec3 m =
          glm::dmat3(glm::cross(d.d[1], d.d[2]), glm::cross(d.d[2], d.d[0]), glm::cross(d.d[0], d.d[1])) * normals[i];
      if (glm::length(m) > 1e-6) {
        EXPECT_LT(glm::length(n[i] - glm::normalize(m)), 1e-9)
            << glm::to_string(orders) << " at " << glm::to_string(params[i]);
      }
    }
  }
}
