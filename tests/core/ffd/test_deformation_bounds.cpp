// Certified deformation-error bounds (core/ffd/deformation_bounds.h): equal to the true error where the theory is
// sharp (a parabola's chord; the long edge of an obtuse triangle under Waldron's bound), never below the measured
// error on random lattices of orders 2–4 (order 2: none across its C⁰ knot planes) and on the teapot's triangles
// under a bend + twist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/ffd/deformation_bounds.h"
#include "core/ffd/ffd.h"
#include "core/scene/primitives.h"
#include "core/spline/knot_vector.h"

namespace trispline::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

TrivariateBSpline<glm::dvec3> lattice_of(int order, int n, const std::function<glm::dvec3(const glm::dvec3&)>& map) {
  const KnotVector k = KnotVector::clamped_uniform(order, n);
  const auto g = k.greville();
  std::vector<glm::dvec3> P;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) P.push_back(map(glm::dvec3(g[x], g[y], g[z])));
  return TrivariateBSpline<glm::dvec3>(k, k, k, std::move(P));
}

TEST(DeformationBounds, ParabolaChordIsTheEqualityCase) {
  // F = (u, v, w + k u²): one quadratic cell, F_uu = (0, 0, 2k) exactly (the control points of a quadratic with the
  // Greville placement reproduce u² only up to a linear term, which does not change second derivatives).
  const double k = 0.8;
  const auto F = lattice_of(3, 3, [&](const glm::dvec3& p) { return p; });
  auto G = F;
  // Quadratic Bézier control points of u² on [0,1]: 0, 0, 1 (at u = 0, ½, 1).
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y) G.control_point(2, y, z).z += k;
  const SecondDerivativeBounds b(G);
  // Right angle at c, e1 along u (length L), e2 along v.
  const double L = 0.6;
  const glm::dvec3 c(0.2, 0.3, 0.5), a = c + glm::dvec3(L, 0, 0), bb = c + glm::dvec3(0, 0.3, 0);
  const double bound = triangle_error_bound(b, a, bb, c, ErrorBound::right_triangle);
  const double truth = triangle_error_sampled(G, a, bb, c, 40);
  EXPECT_NEAR(truth, k * L * L / 4.0, 1e-9) << "the chord of k·u² over length L deviates by k·L²/4";
  EXPECT_NEAR(bound, truth, 1e-9) << "Theorem 4's bound is sharp for a parabola along one leg";
}

TEST(DeformationBounds, NeverBelowTheMeasuredErrorOnRandomLattices) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  std::vector<double> ratios;
  for (int trial = 0; trial < 24; ++trial) {
    const int order = 2 + trial % 3, n = order + 1 + trial % 3;
    std::normal_distribution<double> noise(0.0, 0.25 / n);
    auto F = lattice_of(order, n, [&](const glm::dvec3& p) { return p + glm::dvec3(noise(rng), noise(rng), noise(rng)); });
    const SecondDerivativeBounds b(F);
    for (int t = 0; t < 12; ++t) {
      const glm::dvec3 c(u(rng), u(rng), u(rng));
      const double size = 0.05 + 0.3 * u(rng);
      const glm::dvec3 a = glm::clamp(c + size * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), 0.0, 1.0);
      const glm::dvec3 bb = glm::clamp(c + size * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), 0.0, 1.0);
      const double truth = triangle_error_sampled(F, a, bb, c, 12);
      for (ErrorBound m : {ErrorBound::right_triangle, ErrorBound::enclosing_circle, ErrorBound::best})
        EXPECT_GE(triangle_error_bound(b, a, bb, c, m) * (1 + 1e-12) + 1e-15, truth)
            << "trial " << trial << " triangle " << t << " method " << int(m);
      const double bound = triangle_error_bound(b, a, bb, c);
      if (std::isinf(bound)) {
        EXPECT_EQ(order, 2) << "only a C⁰ (order-2) knot plane leaves a triangle unbounded";
        continue;
      }
      if (truth > 1e-9) ratios.push_back(bound / truth);
      ++checked;
    }
  }
  std::sort(ratios.begin(), ratios.end());
  ASSERT_FALSE(ratios.empty());
  RecordProperty("tightness_median", std::to_string(ratios[ratios.size() / 2]));
  RecordProperty("tightness_worst", std::to_string(ratios.back()));
  EXPECT_GT(checked, 200) << "triangles with a finite bound";
}

TEST(DeformationBounds, TeapotUnderBendAndTwistIsBoundedEverywhere) {
  const TriMesh mesh = make_teapot(8);
  const Embedding e = embed_bounding_box(mesh.positions, EmbeddingAxes{});
  const std::vector<glm::dvec3> params = embed_points(e, mesh.positions);
  // Bend about v and twist about w, cubic 6³.
  const auto F = lattice_of(4, 6, [](const glm::dvec3& p) {
    const double a = 0.6 * (p.z - 0.5), bend = 0.5 * (p.x - 0.5);
    const glm::dvec3 q(0.5 + (p.x - 0.5) * std::cos(a) - (p.y - 0.5) * std::sin(a),
                       0.5 + (p.x - 0.5) * std::sin(a) + (p.y - 0.5) * std::cos(a), p.z);
    return q + glm::dvec3(0.0, 0.0, bend * bend);
  });
  const SecondDerivativeBounds b(F);
  std::size_t checked = 0;
  double worst_ratio = 0.0;
  for (std::size_t f = 0; f < mesh.triangles.size(); f += 5) {
    const glm::uvec3 t = mesh.triangles[f];
    const double truth = triangle_error_sampled(F, params[t.x], params[t.y], params[t.z], 8);
    const double bound = triangle_error_bound(b, params[t.x], params[t.y], params[t.z]);
    EXPECT_GE(bound * (1 + 1e-12) + 1e-15, truth) << "triangle " << f;
    if (truth > 1e-9) worst_ratio = std::max(worst_ratio, bound / truth);
    ++checked;
  }
  EXPECT_GT(checked, 200u);
  RecordProperty("tightness_worst_teapot", std::to_string(worst_ratio));
}

TEST(DeformationBounds, EnclosingCircleOfAnObtuseTriangleIsHalfItsLongestEdge) {
  // F = (u, v, w + u² + v²): F_uu = F_vv = 2 e_w, no mixed terms; M has λ = 2.
  auto F = lattice_of(3, 3, [](const glm::dvec3& p) { return p; });
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) F.control_point(x, y, z).z += (x == 2 ? 1.0 : 0.0) + (y == 2 ? 1.0 : 0.0);
  const SecondDerivativeBounds b(F);
  // Obtuse: the long edge from (0.2,0.5) to (0.8,0.5), the apex just above its middle.
  const glm::dvec3 a(0.2, 0.5, 0.5), bb(0.8, 0.5, 0.5), c(0.5, 0.55, 0.5);
  const double R = 0.3;  // half the longest edge (the circumradius would be 0.925)
  EXPECT_NEAR(triangle_error_bound(b, a, bb, c, ErrorBound::enclosing_circle), 0.5 * R * R * 2.0, 1e-9);
  EXPECT_GE(triangle_error_bound(b, a, bb, c, ErrorBound::enclosing_circle) * (1 + 1e-12),
            triangle_error_sampled(F, a, bb, c, 40))
      << "sharp: the error at the long edge's midpoint is ½R²·2";
}

TEST(DeformationBounds, RefusesPeriodicAndBadLattices) {
  const KnotVector kp = KnotVector::periodic_uniform(3, 5), k = KnotVector::clamped_uniform(3, 3);
  EXPECT_THROW(SecondDerivativeBounds(TrivariateBSpline<glm::dvec3>(kp, k, k, std::vector<glm::dvec3>(45))),
               std::invalid_argument);
  auto F = lattice_of(3, 3, [](const glm::dvec3& p) { return p; });
  F.control_point(1, 1, 1).x = INFINITY;
  EXPECT_THROW(SecondDerivativeBounds{F}, std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
