// BSplineCurve: evaluation against the basis definition, derivatives vs central differences, knot insertion up to
// C^-1 and Bézier pieces leave the curve unchanged, invalid input.
#include <limits>

#include "core/spline/bspline_basis.h"
#include "core/spline/bspline_curve.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

using Curve3 = BSplineCurve<glm::dvec3>;

Curve3 random_curve(test::Rng& rng, int order, bool clamped) {
  const int n = test::uniform_int(rng, order, order + 6);
  KnotVector kv = test::random_knots(rng, order, n, clamped, order);
  return Curve3(kv, test::random_points<glm::dvec3>(rng, n));
}

double max_difference(const Curve3& a, const Curve3& b, const std::vector<double>& ts) {
  double m = 0;
  for (double t : ts) m = std::max(m, test::norm_inf(a.eval(t) - b.eval(t)));
  return m;
}

TEST(Curve, EvalIsSumOfBasisTimesControls) {
  // Linear clamped: C(t) interpolates the control polygon at the Greville abscissae.
  const BSplineCurve<double> c(KnotVector::clamped_uniform(2, 3), {1.0, 5.0, 2.0});
  EXPECT_DOUBLE_EQ(c.eval(0.0), 1.0);
  EXPECT_DOUBLE_EQ(c.eval(0.25), 3.0);
  EXPECT_DOUBLE_EQ(c.eval(0.5), 5.0);
  EXPECT_DOUBLE_EQ(c.eval(1.0), 2.0);
  EXPECT_DOUBLE_EQ(c.eval(2.0), 2.0);  // clamped to the domain
  // Quadratic Bézier midpoint: (P0 + 2 P1 + P2) / 4.
  const BSplineCurve<glm::dvec2> q(KnotVector::clamped_uniform(3, 3), {{0, 0}, {1, 2}, {2, 0}});
  EXPECT_NEAR(q.eval(0.5).x, 1.0, 1e-15);
  EXPECT_NEAR(q.eval(0.5).y, 1.0, 1e-15);
}

TEST(Curve, DerivativesMatchCentralDifferences) {
  test::Rng rng(11);
  const double h = 1e-6;
  for (int order = 1; order <= 5; ++order)
    for (int trial = 0; trial < 10; ++trial) {
      const Curve3 c = random_curve(rng, order, trial % 2 == 0);
      for (int s = 0; s < 20; ++s) {
        const double t = test::param_away_from_knots(rng, c.knots(), 1e-3);
        const auto d = c.derivatives(t, 3);
        const auto dp = c.derivatives(t + h, 2), dm = c.derivatives(t - h, 2);
        EXPECT_LT(test::norm_inf(d[0] - c.eval(t)), 1e-14);
        for (int k = 1; k <= 3; ++k) {
          const glm::dvec3 fd = (dp[k - 1] - dm[k - 1]) / (2 * h);
          EXPECT_LT(test::norm_inf(d[k] - fd), 1e-5 * (1 + test::norm_inf(d[k]))) << "order " << order << " k " << k;
        }
      }
    }
}

TEST(Curve, KnotInsertionLeavesCurveUnchanged) {
  test::Rng rng(12);
  for (int order = 1; order <= 5; ++order)
    for (int trial = 0; trial < 20; ++trial) {
      const Curve3 original = random_curve(rng, order, trial % 2 == 0);
      Curve3 c = original;
      const KnotVector& kv = original.knots();
      // A new knot, an existing knot raised to full multiplicity (C^-1), and the domain ends.
      const double fresh = test::uniform(rng, kv.domain_min(), kv.domain_max());
      c.insert_knot(fresh, test::uniform_int(rng, 1, order));
      const double existing = kv[test::uniform_int(rng, order - 1, kv.control_count())];
      c.insert_knot(existing, order + 2);  // capped at multiplicity = order
      EXPECT_EQ(c.knots().multiplicity(existing), order);
      c.insert_knot(kv.domain_min(), order);
      c.insert_knot(kv.domain_max(), order);
      EXPECT_LE(max_difference(original, c, test::sample_params(rng, c.knots(), 200)), 1e-12) << "order " << order;
    }
}

TEST(Curve, KnotInsertionChangesControlsAsBoehmSays) {
  // Quadratic Bézier on [0,1], insert 0.5: new controls P0, (P0+P1)/2, (P1+P2)/2, P2 (de Casteljau).
  BSplineCurve<double> c(KnotVector::clamped_uniform(3, 3), {0.0, 4.0, 8.0 + 2.0});
  c.insert_knot(0.5);
  ASSERT_EQ(c.control_points().size(), 4u);
  EXPECT_DOUBLE_EQ(c.control_points()[1], 2.0);
  EXPECT_DOUBLE_EQ(c.control_points()[2], 7.0);
  EXPECT_EQ(c.knots().multiplicity(0.5), 1);
}

TEST(Curve, BezierPiecesReproduceTheCurve) {
  test::Rng rng(13);
  for (int order = 1; order <= 5; ++order)
    for (int trial = 0; trial < 20; ++trial) {
      const Curve3 c = random_curve(rng, order, trial % 2 == 0);
      const auto pieces = c.bezier_pieces();
      int non_empty = 0;
      for (int s = order - 1; s < c.knots().control_count(); ++s) non_empty += c.knots()[s] < c.knots()[s + 1];
      ASSERT_EQ(static_cast<int>(pieces.size()), non_empty);
      for (const Curve3& piece : pieces) {
        ASSERT_EQ(piece.control_points().size(), static_cast<std::size_t>(order));
        EXPECT_TRUE(piece.knots().is_clamped());
        for (int s = 0; s <= 20; ++s) {
          const double a = piece.knots().domain_min(), b = piece.knots().domain_max();
          // Stay left of the piece's end: the curve may break there (C^-1) and evaluates its right side.
          const double tt = s == 20 ? std::nextafter(b, a) : a + (b - a) * s / 20;
          EXPECT_LE(test::norm_inf(piece.eval(tt) - c.eval(tt)), 1e-12) << "order " << order << " t " << tt;
        }
      }
      const Curve3 e = c.bezier_extracted();
      EXPECT_TRUE(e.knots().is_clamped());
      EXPECT_LE(max_difference(c, e, test::sample_params(rng, c.knots(), 200)), 1e-12);
    }
}

TEST(Curve, InvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  test::expect_invalid(
      [] {
        BSplineCurve<double>(KnotVector::clamped_uniform(3, 4), {1, 2, 3});
      },
      "wrong control point count: got 3");
  test::expect_invalid(
      [&] {
        BSplineCurve<double>(KnotVector::clamped_uniform(2, 3), {1, nan, 3});
      },
      "control point 1 is not finite");
  test::expect_invalid(
      [] {
        BSplineCurve<double>(KnotVector::clamped_uniform(5, 3), {1, 2, 3});
      },
      "exceeds control count");
  BSplineCurve<double> c(KnotVector::clamped_uniform(3, 4), {1, 2, 3, 4});
  test::expect_invalid([&] { c.insert_knot(1.5); }, "outside the domain");
  test::expect_invalid([&] { c.insert_knot(nan); }, "outside the domain");
  test::expect_invalid([&] { c.eval(nan); }, "NaN");
}

}  // namespace
}  // namespace trispline::core
