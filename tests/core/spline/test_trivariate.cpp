// TrivariateBSpline: identity / affine lattices (linear precision at Greville abscissae), Jacobian and det J,
// partials vs central differences, knot insertion and Bézier extraction leave F unchanged, invalid input.
#include <limits>

#include "core/spline/trivariate_bspline.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

using Volume = TrivariateBSpline<glm::dvec3>;

// Lattice of the affine map x ↦ A·x + b with control points at the Greville abscissae.
Volume affine_lattice(KnotVector ku, KnotVector kv, KnotVector kw, const glm::dmat3& A, const glm::dvec3& b) {
  const auto gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> P;
  for (double w : gw)
    for (double v : gv)
      for (double u : gu) P.push_back(A * glm::dvec3(u, v, w) + b);
  return Volume(std::move(ku), std::move(kv), std::move(kw), std::move(P));
}

template <class T>
TrivariateBSpline<T> random_volume(test::Rng& rng, glm::ivec3 order, bool clamped) {
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) n[a] = test::uniform_int(rng, order[a], order[a] + 3);
  return TrivariateBSpline<T>(test::random_knots(rng, order.x, n[0], clamped, order.x),
                              test::random_knots(rng, order.y, n[1], !clamped, order.y),
                              test::random_knots(rng, order.z, n[2], clamped, order.z),
                              test::random_points<T>(rng, static_cast<std::size_t>(n[0] * n[1] * n[2])));
}

template <class T>
double max_difference(test::Rng& rng, const TrivariateBSpline<T>& a, const TrivariateBSpline<T>& b) {
  double m = 0;
  const auto us = test::sample_params(rng, a.knots(0), 6), vs = test::sample_params(rng, a.knots(1), 6),
             ws = test::sample_params(rng, a.knots(2), 6);
  for (double u : us)
    for (double v : vs)
      for (double w : ws) m = std::max(m, test::norm_inf(a.eval({u, v, w}) - b.eval({u, v, w})));
  return m;
}

TEST(Trivariate, IdentityLatticeReproducesPoints) {
  test::Rng rng(31);
  for (int order = 2; order <= 5; ++order) {
    const bool random_knots = order % 2 == 1;
    auto knots = [&](int n) {
      return random_knots ? test::random_knots(rng, order, n, true, order - 1) : KnotVector::clamped_uniform(order, n);
    };
    const Volume F = affine_lattice(knots(order + 2), knots(order), knots(order + 3), glm::dmat3(1.0), glm::dvec3(0));
    for (int s = 0; s < 300; ++s) {
      const glm::dvec3 x(test::uniform(rng, 0, 1), test::uniform(rng, 0, 1), test::uniform(rng, 0, 1));
      EXPECT_LE(test::norm_inf(F.eval(x) - x), 1e-12) << "order " << order;
      const glm::dmat3 J = jacobian(F, x);
      for (int c = 0; c < 3; ++c) EXPECT_LE(test::norm_inf(J[c] - glm::dmat3(1.0)[c]), 1e-12);
      EXPECT_NEAR(jacobian_determinant(F, x), 1.0, 1e-12);
    }
    EXPECT_LE(test::norm_inf(F.eval({1, 1, 1}) - glm::dvec3(1)), 1e-12);
    EXPECT_LE(test::norm_inf(F.eval({0, 0, 0})), 1e-12);
  }
}

TEST(Trivariate, AffineLatticeJacobianIsTheLinearPart) {
  const glm::dmat3 A(glm::dvec3(2, 0.5, 0), glm::dvec3(-0.3, 1, 0.2), glm::dvec3(0.1, 0, 3));  // columns
  const Volume F = affine_lattice(KnotVector::clamped_uniform(3, 4), KnotVector::clamped_uniform(4, 5),
                                  KnotVector::clamped_uniform(2, 3), A, glm::dvec3(1, 2, 3));
  for (const glm::dvec3& x : {glm::dvec3(0.2, 0.3, 0.9), glm::dvec3(0.71, 0.05, 0.5)}) {
    const glm::dmat3 J = jacobian(F, x);
    for (int c = 0; c < 3; ++c) EXPECT_LE(test::norm_inf(J[c] - A[c]), 1e-12) << "column " << c;
    EXPECT_NEAR(jacobian_determinant(F, x), glm::determinant(A), 1e-12);
    EXPECT_LE(test::norm_inf(F.eval(x) - (A * x + glm::dvec3(1, 2, 3))), 1e-12);
  }
}

TEST(Trivariate, PartialsMatchCentralDifferences) {
  test::Rng rng(32);
  const double h = 1e-6;
  for (int trial = 0; trial < 25; ++trial) {
    const glm::ivec3 order(1 + trial % 5, 1 + (trial / 5) % 5, 2 + trial % 4);
    const Volume F = random_volume<glm::dvec3>(rng, order, trial % 2 == 0);
    for (int s = 0; s < 8; ++s) {
      glm::dvec3 x;
      for (int a = 0; a < 3; ++a) x[a] = test::param_away_from_knots(rng, F.knots(a), 1e-3);
      const auto f1 = F.eval_first(x);
      const auto f2 = F.eval_second(x);
      EXPECT_LE(test::norm_inf(f1.value - F.eval(x)), 1e-14);
      for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = h;
        const glm::dvec3 fd = (F.eval(x + e) - F.eval(x - e)) / (2 * h);
        EXPECT_LE(test::norm_inf(f1.d[a] - fd), 1e-5 * (1 + test::norm_inf(f1.d[a]))) << "axis " << a;
        EXPECT_LE(test::norm_inf(f2.d[a] - f1.d[a]), 1e-14);
        const auto p = F.eval_first(x + e), m = F.eval_first(x - e);
        for (int b = 0; b < 3; ++b) {
          const glm::dvec3 fd2 = (p.d[b] - m.d[b]) / (2 * h);  // ∂/∂a of ∂F/∂b
          EXPECT_LE(test::norm_inf(f2.dd[a][b] - fd2), 1e-5 * (1 + test::norm_inf(f2.dd[a][b])))
              << "dd[" << a << "][" << b << "] orders " << order.x << order.y << order.z;
        }
      }
    }
  }
}

TEST(Trivariate, KnotInsertionLeavesFunctionUnchanged) {
  test::Rng rng(33);
  for (int trial = 0; trial < 25; ++trial) {
    const glm::ivec3 order(1 + trial % 5, 1 + (trial * 3) % 5, 1 + (trial / 5) % 5);
    const Volume original = random_volume<glm::dvec3>(rng, order, trial % 2 == 1);
    Volume F = original;
    for (int axis = 0; axis < 3; ++axis) {
      const KnotVector& kv = original.knots(axis);
      F.insert_knot(axis, test::uniform(rng, kv.domain_min(), kv.domain_max()), test::uniform_int(rng, 1, kv.order()));
      const double existing = kv[test::uniform_int(rng, kv.order() - 1, kv.control_count())];
      F.insert_knot(axis, existing, kv.order());  // C^-1
      EXPECT_EQ(F.knots(axis).multiplicity(existing), kv.order());
    }
    const glm::ivec3 c = F.control_counts();
    EXPECT_EQ(F.control_points().size(), static_cast<std::size_t>(c.x) * c.y * c.z);
    EXPECT_LE(max_difference(rng, original, F), 1e-12) << "trial " << trial;
  }
}

TEST(Trivariate, BezierExtractionLeavesFunctionUnchanged) {
  test::Rng rng(34);
  for (int trial = 0; trial < 15; ++trial) {
    const glm::ivec3 order(1 + trial % 5, 1 + (trial * 2) % 5, 1 + (trial / 3) % 5);
    const auto F = random_volume<double>(rng, order, trial % 2 == 0);
    const auto B = F.bezier_extracted();
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_TRUE(B.knots(axis).is_clamped());
      for (double k : B.knots(axis).knots()) EXPECT_EQ(B.knots(axis).multiplicity(k), B.orders()[axis]);
    }
    EXPECT_LE(max_difference(rng, F, B), 1e-12) << "trial " << trial;
  }
}

TEST(Trivariate, ScalarAndVectorAgreeComponentwise) {
  test::Rng rng(35);
  const auto F = random_volume<glm::dvec3>(rng, {3, 2, 4}, true);
  std::vector<double> y;
  for (const auto& p : F.control_points()) y.push_back(p.y);
  const TrivariateBSpline<double> G(F.knots(0), F.knots(1), F.knots(2), y);
  for (int s = 0; s < 50; ++s) {
    const glm::dvec3 x(test::uniform(rng, 0, 1), test::uniform(rng, 0, 1), test::uniform(rng, 0, 1));
    EXPECT_EQ(G.eval(x), F.eval(x).y);  // same operation order → bit-identical
    EXPECT_EQ(G.eval_second(x).dd[0][2], F.eval_second(x).dd[0][2].y);
  }
}

TEST(Trivariate, InvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const KnotVector k2 = KnotVector::clamped_uniform(2, 2);
  const KnotVector k3 = KnotVector::clamped_uniform(2, 3);
  test::expect_invalid([&] { TrivariateBSpline<double>(k2, k3, k2, std::vector<double>(8, 0.0)); },
                       "wrong control point count: got 8, the knot vectors need 12");
  std::vector<glm::dvec3> P(8, glm::dvec3(0.0));
  P[5].z = nan;
  test::expect_invalid([&] { Volume(k2, k2, k2, P); }, "control point 5 is not finite");
  P[5].z = 0;
  Volume F(k2, k2, k2, P);
  test::expect_invalid([&] { F.insert_knot(3, 0.5); }, "axis");
  test::expect_invalid([&] { F.insert_knot(1, -0.5); }, "outside the domain");
  test::expect_invalid([&] { F.eval({0.5, nan, 0.5}); }, "NaN");
}

}  // namespace
}  // namespace trispline::core
