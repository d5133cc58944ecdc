// Certified deformation-error bounds (core/ffd/deformation_bounds.h): equal to the true error where the theory is
// sharp (a parabola's chord; the long edge of an obtuse triangle under Waldron's bound), never below the measured
// error on random lattices of orders 2–4 (order 2: none across its C⁰ knot planes) and on the teapot's triangles
// under a bend + twist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "core/ffd/deformation_bounds.h"
#include "core/ffd/ffd.h"
#include "core/mesh/mesh_io.h"
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
  std::vector<double> ratios, normal_ratios;
  for (int trial = 0; trial < 24; ++trial) {
    const int order = 2 + trial % 3, n = order + 1 + trial % 3;
    std::normal_distribution<double> noise(0.0, 0.25 / n);
    auto F =
        lattice_of(order, n, [&](const glm::dvec3& p) { return p + glm::dvec3(noise(rng), noise(rng), noise(rng)); });
    const SecondDerivativeBounds b(F);
    for (int t = 0; t < 12; ++t) {
      const glm::dvec3 c(u(rng), u(rng), u(rng));
      const double size = 0.05 + 0.3 * u(rng);
      const glm::dvec3 a = glm::clamp(c + size * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), 0.0, 1.0);
      const glm::dvec3 bb = glm::clamp(c + size * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), 0.0, 1.0);
      const double truth = triangle_error_sampled(F, a, bb, c, 12);
      for (ErrorBound m :
           {ErrorBound::right_triangle, ErrorBound::circumcircle, ErrorBound::enclosing_circle, ErrorBound::best})
        EXPECT_GE(triangle_error_bound(b, a, bb, c, m) * (1 + 1e-12) + 1e-15, truth)
            << "trial " << trial << " triangle " << t << " method " << int(m);
      const glm::dvec3 fn = glm::cross(F.eval(a) - F.eval(c), F.eval(bb) - F.eval(c));
      if (glm::length(fn) > 1e-12) {
        const glm::dvec3 n = glm::normalize(fn);
        const double along = triangle_normal_error_sampled(F, a, bb, c, n, 12);
        const double nb = triangle_normal_error_bound(b, a, bb, c, n);
        EXPECT_GE(nb * (1 + 1e-12) + 1e-15, along) << "normal bound, trial " << trial << " triangle " << t;
        EXPECT_LE(nb, triangle_error_bound(b, a, bb, c) * (1 + 1e-12)) << "projecting never loosens the bound";
        if (along > 1e-9 && std::isfinite(nb)) normal_ratios.push_back(nb / along);
      }
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
  std::sort(normal_ratios.begin(), normal_ratios.end());
  ASSERT_GT(normal_ratios.size(), 100u);
  RecordProperty("normal_tightness_median", std::to_string(normal_ratios[normal_ratios.size() / 2]));
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
    const glm::dvec3 fa = F.eval(params[t.x]), fb = F.eval(params[t.y]), fc = F.eval(params[t.z]);
    const glm::dvec3 fn = glm::cross(fb - fa, fc - fa);
    if (glm::length(fn) > 1e-15) {
      const glm::dvec3 n = glm::normalize(fn);
      EXPECT_GE(triangle_normal_error_bound(b, params[t.x], params[t.y], params[t.z], n) * (1 + 1e-12) + 1e-15,
                triangle_normal_error_sampled(F, params[t.x], params[t.y], params[t.z], n, 8))
          << "normal bound, triangle " << f;
    }
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

TEST(DeformationBounds, ParaboloidOverAnAcuteTriangleIsTheCircleEqualityCase) {
  // F = (u, v, w + u² + v²): over a triangle in a w = const plane, F∘T − T_F = |x − O|² − r² along e_w (O, r the
  // circumcentre and circumradius: a quadratic with Hessian 2I vanishing at the three corners), largest at O, r².
  // The circle bounds give ½ r² λ with λ = 2 exactly: equality (Lemma 1: the circumcentre is the farthest point).
  auto F = lattice_of(3, 3, [](const glm::dvec3& p) { return p; });
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) F.control_point(x, y, z).z += (x == 2 ? 1.0 : 0.0) + (y == 2 ? 1.0 : 0.0);
  const SecondDerivativeBounds b(F);
  const double r = 0.3;
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const double th = 0.4 + 2.0 * kPi * k / 3.0;  // equilateral, circumcentre (0.5, 0.5)
    p[k] = glm::dvec3(0.5 + r * std::cos(th), 0.5 + r * std::sin(th), 0.5);
  }
  const double truth = triangle_error_sampled(F, p[0], p[1], p[2], 30);
  EXPECT_NEAR(truth, r * r, 1e-12) << "Newton finds the circumcentre";
  EXPECT_NEAR(triangle_error_bound(b, p[0], p[1], p[2], ErrorBound::circumcircle), r * r, 1e-12);
  EXPECT_NEAR(triangle_error_bound(b, p[0], p[1], p[2], ErrorBound::enclosing_circle), r * r, 1e-12);
  EXPECT_GE(triangle_error_bound(b, p[0], p[1], p[2], ErrorBound::right_triangle), truth);
  // Obtuse: the circumcircle grows without bound as the apex flattens, the enclosing circle stays at half the long
  // edge; both still hold.
  const glm::dvec3 a(0.2, 0.5, 0.5), bb(0.8, 0.5, 0.5), c(0.5, 0.52, 0.5);
  const double circum = triangle_error_bound(b, a, bb, c, ErrorBound::circumcircle),
               enclosing = triangle_error_bound(b, a, bb, c, ErrorBound::enclosing_circle);
  EXPECT_GT(circum, 10.0 * enclosing);
  EXPECT_GE(enclosing * (1 + 1e-12), triangle_error_sampled(F, a, bb, c, 30)) << "equal up to rounding: sharp";
  EXPECT_TRUE(std::isinf(triangle_error_bound(b, a, bb, (a + bb) * 0.5, ErrorBound::circumcircle)))
      << "a degenerate triangle has no circumcircle";
}

TEST(DeformationBounds, StanfordBunnyTrianglesInRandomLatticesNeverExceedTheirBounds) {
  const std::filesystem::path path = TRISPLINE_SOURCE_DIR "/assets/data/bunny.obj";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run scripts/fetch_assets.sh";
  const TriMesh bunny = load_mesh(path.string());
  ASSERT_GT(bunny.triangles.size(), 60000u);
  const Embedding e = embed_bounding_box(bunny.positions, {0, 1});
  const std::vector<glm::dvec3> params = embed_points(e, bunny.positions);
  std::mt19937 rng(11);
  std::vector<double> ratios;
  std::size_t checked = 0;
  for (int order : {3, 4}) {
    // A random lattice over the bunny's box: 6 controls per axis displaced by up to 30 % of a cell (world units).
    Aabb box;
    for (const glm::dvec3& q : bunny.positions) box.extend(q);
    const glm::dvec3 size = box.size();
    std::normal_distribution<double> noise(0.0, 0.3 / 6.0);
    auto F = lattice_of(order, 6, [&](const glm::dvec3& q) {
      return glm::inverse(e.linear) * (q - e.offset) + size * glm::dvec3(noise(rng), noise(rng), noise(rng));
    });
    const SecondDerivativeBounds b(F);
    const std::vector<double> bounds = triangle_error_bounds(b, params, bunny.triangles);
    for (std::size_t f = order; f < bunny.triangles.size(); f += 37) {  // ~1,900 triangles per lattice
      const glm::uvec3 t = bunny.triangles[f];
      const double truth = triangle_error_sampled(F, params[t.x], params[t.y], params[t.z], 6);
      for (ErrorBound m : {ErrorBound::right_triangle, ErrorBound::circumcircle, ErrorBound::enclosing_circle})
        EXPECT_GE(triangle_error_bound(b, params[t.x], params[t.y], params[t.z], m) * (1 + 1e-12) + 1e-15, truth)
            << "order " << order << " triangle " << f << " " << error_bound_name(m);
      ASSERT_TRUE(std::isfinite(bounds[f]));
      EXPECT_GE(bounds[f] * (1 + 1e-12) + 1e-15, truth) << "order " << order << " triangle " << f;
      if (truth > 1e-12) ratios.push_back(bounds[f] / truth);
      ++checked;
    }
  }
  ASSERT_GT(checked, 3000u);
  std::sort(ratios.begin(), ratios.end());
  RecordProperty("bunny_tightness_median", std::to_string(ratios[ratios.size() / 2]));
  RecordProperty("bunny_tightness_worst", std::to_string(ratios.back()));
}

TEST(DeformationBounds, NormalBoundIgnoresSlidingWithinThePlane) {
  // F = (u + k u², v, w): every w = const plane maps into itself, so a triangle in such a plane keeps its surface in
  // the drawn plane — the projected error is 0 and so is the normal bound (the seed's reparametrization example of
  // §3.2.2), while the full error and its bound are not.
  const double k = 0.5;
  auto F = lattice_of(3, 3, [](const glm::dvec3& p) { return p; });
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y) F.control_point(2, y, z).x += k;
  const SecondDerivativeBounds b(F);
  const glm::dvec3 a(0.1, 0.2, 0.4), bb(0.9, 0.3, 0.4), c(0.4, 0.8, 0.4);
  const glm::dvec3 n = glm::normalize(glm::cross(F.eval(bb) - F.eval(a), F.eval(c) - F.eval(a)));
  EXPECT_NEAR(std::abs(n.z), 1.0, 1e-12);
  EXPECT_NEAR(triangle_normal_error_bound(b, a, bb, c, n), 0.0, 1e-15) << "0 up to the rounding of de Casteljau";
  EXPECT_GT(triangle_error_sampled(F, a, bb, c, 24), 0.01);
  EXPECT_GE(triangle_error_bound(b, a, bb, c) * (1 + 1e-12), triangle_error_sampled(F, a, bb, c, 24));
  // Tilted out of the plane, the normal bound is back and still holds.
  const glm::dvec3 c2(0.4, 0.8, 0.9);
  const glm::dvec3 n2 = glm::normalize(glm::cross(F.eval(bb) - F.eval(a), F.eval(c2) - F.eval(a)));
  const double nb = triangle_normal_error_bound(b, a, bb, c2, n2);
  EXPECT_GT(nb, 0.0);
  EXPECT_GE(nb * (1 + 1e-12), triangle_normal_error_sampled(F, a, bb, c2, n2, 24));
}

TEST(DeformationBounds, PeriodicLatticeIsBoundedAcrossItsSeam) {
  // A ring: u periodic (period 6, cubic), the annulus r ∈ [1, 1.5] in v, height in w; control points jittered.
  const KnotVector kp = KnotVector::periodic_uniform(4, 6), kv = KnotVector::clamped_uniform(3, 3),
                   kw = KnotVector::clamped_uniform(2, 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0.0, 0.05);
  std::vector<glm::dvec3> P;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 6; ++i) {
        const double th = 2.0 * kPi * i / 6.0, r = 1.0 + 0.25 * j;
        P.push_back(glm::dvec3(r * std::cos(th), r * std::sin(th), 0.5 * k) +
                    glm::dvec3(jitter(rng), jitter(rng), jitter(rng)));
      }
  const TrivariateBSpline<glm::dvec3> F(kp, kv, kw, std::move(P));
  const SecondDerivativeBounds b(F);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int across = 0;
  for (int t = 0; t < 200; ++t) {
    // Parameters past the domain along u (an FFD wraps them), some triangles straddling u = 1 and u = 2.
    const glm::dvec3 c(0.8 + 1.4 * u(rng), u(rng), u(rng));
    const double size = 0.05 + 0.3 * u(rng);
    auto corner = [&] {
      return glm::clamp(c + size * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5), glm::dvec3(-5, 0, 0),
                        glm::dvec3(5, 1, 1));
    };
    const glm::dvec3 a = corner(), bb = corner();
    const double lo = std::min({a.x, bb.x, c.x}), hi = std::max({a.x, bb.x, c.x});
    across += std::floor(lo) != std::floor(hi);
    const double bound = triangle_error_bound(b, a, bb, c);
    ASSERT_TRUE(std::isfinite(bound));
    EXPECT_GE(bound * (1 + 1e-12) + 1e-15, triangle_error_sampled(F, a, bb, c, 12)) << "triangle " << t;
  }
  EXPECT_GT(across, 10) << "triangles straddling the seam";
}

TEST(DeformationBounds, NoBoundOutsideTheDomainWhereFIsClamped) {
  const auto F = lattice_of(4, 5, [](const glm::dvec3& p) { return p + glm::dvec3(0.0, 0.0, p.x * p.x); });
  const SecondDerivativeBounds b(F);
  EXPECT_TRUE(std::isfinite(triangle_error_bound(b, {0.2, 0.2, 0.5}, {1.0, 0.2, 0.5}, {0.2, 0.9, 0.5})));
  EXPECT_TRUE(std::isinf(triangle_error_bound(b, {0.2, 0.2, 0.5}, {1.3, 0.2, 0.5}, {0.2, 0.9, 0.5})));
}

TEST(DeformationBounds, RefusesBadLattices) {
  auto F = lattice_of(3, 3, [](const glm::dvec3& p) { return p; });
  F.control_point(1, 1, 1).x = INFINITY;
  EXPECT_THROW(SecondDerivativeBounds{F}, std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
