// Periodic (closed) knot vectors (seed Fig. 4.5): KnotVector::periodic_uniform, SpanBasis and TrivariateBSpline
// wrapping, C^(p−1) continuity across the seam, equality with the unwrapped uniform B-spline.
#include "core/spline/bspline_basis.h"
#include "core/spline/span_basis.h"
#include "core/spline/trivariate_bspline.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

using Tri = TrivariateBSpline<glm::dvec3>;

// Lattice periodic along u with `period` stored controls (random), clamped along v and w.
Tri periodic_lattice(test::Rng& rng, int order, int period) {
  KnotVector ku = KnotVector::periodic_uniform(order, period);
  KnotVector kv = KnotVector::clamped_uniform(3, 4), kw = KnotVector::clamped_uniform(2, 3);
  return Tri(std::move(ku), std::move(kv), std::move(kw),
             test::random_points<glm::dvec3>(rng, static_cast<std::size_t>(period) * 4 * 3));
}

TEST(Periodic, KnotVectorLayout) {
  for (int order = 1; order <= 5; ++order) {
    const int p = order - 1, period = 6;
    const KnotVector kv = KnotVector::periodic_uniform(order, period);
    ASSERT_EQ(static_cast<int>(kv.knots().size()), period + 2 * p + 1);
    for (int i = 0; i <= period + 2 * p; ++i) EXPECT_DOUBLE_EQ(kv[i], (i - p) / 6.0);
    EXPECT_EQ(kv.control_count(), period + p);
    EXPECT_EQ(kv.stored_control_count(), period);
    EXPECT_TRUE(kv.is_periodic());
    EXPECT_EQ(kv.period(), period);
    EXPECT_DOUBLE_EQ(kv.domain_min(), 0.0);
    EXPECT_DOUBLE_EQ(kv.domain_max(), 1.0);
    EXPECT_FALSE(kv.is_clamped());
    EXPECT_TRUE(kv.has_uniform_spans());
    EXPECT_DOUBLE_EQ(kv.wrap_or_clamp(1.25), 0.25);
    EXPECT_DOUBLE_EQ(kv.wrap_or_clamp(-0.25), 0.75);
    EXPECT_EQ(kv.find_span(1.3), kv.find_span(0.3));
    EXPECT_EQ(kv.find_span(-0.7), kv.find_span(0.3));
  }
  const KnotVector c = KnotVector::clamped_uniform(3, 5);
  EXPECT_FALSE(c.is_periodic());
  EXPECT_EQ(c.period(), 0);
  EXPECT_EQ(c.stored_control_count(), 5);
  EXPECT_DOUBLE_EQ(c.wrap_or_clamp(1.25), 1.0);
  test::expect_invalid([] { KnotVector::periodic_uniform(3, 0); }, "period");
  test::expect_invalid([] { KnotVector::periodic_uniform(0, 4); }, "order");
}

TEST(Periodic, SpanBasisWrapsAndMatchesReference) {
  test::Rng rng(5);
  for (int order = 2; order <= 4; ++order) {
    const KnotVector kv = KnotVector::periodic_uniform(order, 5);
    const SpanBasis<double> sb(kv);
    EXPECT_TRUE(sb.periodic());
    EXPECT_EQ(sb.period(), 5);
    EXPECT_EQ(sb.span_count(), 5);
    std::vector<double> N(order), dN(order), N2(order), dN2(order), ref(2 * order);
    for (int s = 0; s < 200; ++s) {
      const double t = test::uniform(rng, 0.0, 1.0);
      const int first = sb.eval(t, N.data(), dN.data());
      EXPECT_GE(first, 0);
      EXPECT_LT(first, 5);
      basis_derivatives(kv, kv.find_span(t), t, 1, ref.data());
      for (int r = 0; r < order; ++r) {
        EXPECT_NEAR(N[r], ref[r], 1e-12);
        EXPECT_NEAR(dN[r], ref[order + r], 1e-10);
      }
      for (double shift : {1.0, -1.0, 3.0}) {
        EXPECT_EQ(sb.eval(t + shift, N2.data(), dN2.data()), first) << t + shift;
        for (int r = 0; r < order; ++r) EXPECT_NEAR(N2[r], N[r], 1e-12);
      }
    }
  }
}

TEST(Periodic, TrivariateIsPeriodicAlongU) {
  test::Rng rng(7);
  for (int order = 2; order <= 5; ++order) {
    const Tri F = periodic_lattice(rng, order, 7);
    EXPECT_EQ(F.control_counts(), glm::ivec3(7, 4, 3));
    for (int s = 0; s < 100; ++s) {
      const glm::dvec3 p(test::uniform(rng, 0, 1), test::uniform(rng, 0, 1), test::uniform(rng, 0, 1));
      const glm::dvec3 f = F.eval(p);
      for (double shift : {1.0, -1.0, 2.0, -3.0}) {
        EXPECT_LT(test::norm_inf(F.eval(p + glm::dvec3(shift, 0, 0)) - f), 1e-12) << order << " " << shift;
        const auto d0 = F.eval_first(p), d1 = F.eval_first(p + glm::dvec3(shift, 0, 0));
        for (int a = 0; a < 3; ++a) EXPECT_LT(test::norm_inf(d1.d[a] - d0.d[a]), 1e-10);
      }
      // v is clamped (not periodic): beyond the domain the value is that at the boundary.
      EXPECT_LT(test::norm_inf(F.eval({p.x, 1.7, p.z}) - F.eval({p.x, 1.0, p.z})), 1e-15);
    }
  }
}

TEST(Periodic, ContinuityAcrossTheSeamIsCpMinus1) {
  test::Rng rng(9);
  const double eps = 1e-7;
  for (int order = 2; order <= 4; ++order) {
    const int p = order - 1;
    const Tri F = periodic_lattice(rng, order, 5);
    for (int s = 0; s < 20; ++s) {
      const double v = test::uniform(rng, 0, 1), w = test::uniform(rng, 0, 1);
      const auto L = F.eval_second({-eps, v, w}), R = F.eval_second({eps, v, w});
      // Derivatives of order < p are continuous: their jump over 2ε is O(ε) (scale: control points in [−1,1],
      // a d-th derivative scales with period^d).
      EXPECT_LT(test::norm_inf(L.value - R.value), 1e3 * eps);
      if (p >= 2) {
        EXPECT_LT(test::norm_inf(L.d[0] - R.d[0]), 1e4 * eps) << "order " << order;
      }
      if (p >= 3) {
        EXPECT_LT(test::norm_inf(L.dd[0][0] - R.dd[0][0]), 1e5 * eps) << "order " << order;
      }
      // And the seam is not special: the same holds around an interior knot (sanity of the tolerance)...
      const auto Li = F.eval_second({0.4 - eps, v, w}), Ri = F.eval_second({0.4 + eps, v, w});
      EXPECT_LT(test::norm_inf(Li.value - Ri.value), 1e3 * eps);
      // ...while the (p)-th derivative does jump at the seam for random controls (the test can fail).
      if (p == 1) {
        EXPECT_GT(test::norm_inf(L.d[0] - R.d[0]), 1e-3);
      }
      if (p == 2) {
        EXPECT_GT(test::norm_inf(L.dd[0][0] - R.dd[0][0]), 1e-3);
      }
    }
  }
}

TEST(Periodic, EqualsUnwrappedUniformSplineWithDuplicatedControls) {
  test::Rng rng(11);
  for (int order = 2; order <= 4; ++order) {
    const int p = order - 1, period = 6;
    const Tri F = periodic_lattice(rng, order, period);
    // Non-periodic uniform knots over period + p controls: t_i = (i − p)/period, the same knots.
    const KnotVector ku = KnotVector::uniform(order, period + p);
    for (int i = 0; i < period + 2 * p + 1; ++i) ASSERT_DOUBLE_EQ(ku[i], F.knots(0)[i]);
    std::vector<glm::dvec3> cps;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < period + p; ++i) cps.push_back(F.control_point(i % period, j, k));
    const Tri G(ku, F.knots(1), F.knots(2), cps);
    for (int s = 0; s < 300; ++s) {
      const glm::dvec3 q(test::uniform(rng, 0, 1), test::uniform(rng, 0, 1), test::uniform(rng, 0, 1));
      EXPECT_LT(test::norm_inf(F.eval(q) - G.eval(q)), 1e-13);
      const auto a = F.eval_first(q), b = G.eval_first(q);
      for (int d = 0; d < 3; ++d) EXPECT_LT(test::norm_inf(a.d[d] - b.d[d]), 1e-11);
    }
  }
}

TEST(Periodic, RefinementIsRejectedAndCountsAreChecked) {
  test::Rng rng(13);
  Tri F = periodic_lattice(rng, 3, 5);
  test::expect_invalid([&] { F.insert_knot(0, 0.5); }, "periodic");
  test::expect_invalid([&] { (void)F.bezier_extracted(); }, "periodic");
  F.insert_knot(1, 0.3);  // other axes still refine
  EXPECT_EQ(F.control_counts(), glm::ivec3(5, 5, 3));
  // Control points for the unwrapped count (period + p) are a count mismatch.
  test::expect_invalid(
      [] {
        Tri(KnotVector::periodic_uniform(3, 5), KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
            std::vector<glm::dvec3>(7 * 2 * 2));
      },
      "count");
}

}  // namespace
}  // namespace trispline::core
