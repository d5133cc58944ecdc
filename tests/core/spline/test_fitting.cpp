// Least-squares fitting: parametrisations, recovery of a spline sampled from itself, end-point interpolation,
// least-squares optimality, degenerate input.
#include <limits>

#include "core/spline/fitting.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

// Sorted parameters from 0 to 1 with `per_span` random samples inside every non-empty span of kv, topped up with
// random ones to twice the control count.
std::vector<double> params_covering(test::Rng& rng, const KnotVector& kv, int per_span) {
  std::vector<double> t = {kv.domain_min(), kv.domain_max()};
  for (int s = kv.order() - 1; s < kv.control_count(); ++s)
    if (kv[s] < kv[s + 1])
      for (int i = 0; i < per_span; ++i) t.push_back(test::uniform(rng, kv[s], kv[s + 1]));
  while (static_cast<int>(t.size()) < 2 * kv.control_count())
    t.push_back(test::uniform(rng, kv.domain_min(), kv.domain_max()));
  std::sort(t.begin(), t.end());
  return t;
}

TEST(Parametrize, UniformChordCentripetal) {
  const std::vector<glm::dvec2> P = {{0, 0}, {1, 0}, {1, 4}, {1, 4}, {2, 4}};
  const auto u = parametrize(P, Parametrization::Uniform);
  const auto c = parametrize(P, Parametrization::ChordLength);
  const auto z = parametrize(P, Parametrization::Centripetal);
  const std::vector<double> eu = {0, 0.25, 0.5, 0.75, 1}, ec = {0, 1.0 / 6, 5.0 / 6, 5.0 / 6, 1},
                            ez = {0, 0.25, 0.75, 0.75, 1};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(u[i], eu[i], 1e-15);
    EXPECT_NEAR(c[i], ec[i], 1e-15);
    EXPECT_NEAR(z[i], ez[i], 1e-15);
  }
  EXPECT_EQ(c.back(), 1.0);
  // Zero total length falls back to uniform.
  const auto d = parametrize(std::vector<double>{3, 3, 3}, Parametrization::ChordLength);
  EXPECT_NEAR(d[1], 0.5, 1e-15);
  test::expect_invalid([] { parametrize(std::vector<double>{1.0}, Parametrization::Uniform); }, "at least 2 points");
}

TEST(FitCurve, RecoversSplineSampledFromItselfWithSameKnots) {
  test::Rng rng(41);
  for (int order = 1; order <= 5; ++order)
    for (int trial = 0; trial < 10; ++trial) {
      const int n = test::uniform_int(rng, std::max(order, 2), order + 8);
      const KnotVector kv = test::random_knots(rng, order, n, true, std::max(1, order - 1));
      const BSplineCurve<glm::dvec3> truth(kv, test::random_points<glm::dvec3>(rng, n));
      const auto t = params_covering(rng, kv, 3);
      std::vector<glm::dvec3> pts;
      for (double x : t) pts.push_back(truth.eval(x));
      const auto fit = fit_curve(pts, t, kv);
      for (int i = 0; i < n; ++i)
        EXPECT_LE(test::norm_inf(fit.control_points()[i] - truth.control_points()[i]), 1e-9) << order << " " << i;
    }
}

TEST(FitCurve, RecoversSplineWithClampedForFitKnots) {
  test::Rng rng(42);
  for (int order = 2; order <= 5; ++order) {
    const int n = order + 4;
    for (int P : {n, 3 * n}) {  // interpolation and approximation
      std::vector<double> t(P);
      for (auto& x : t) x = test::uniform(rng, 0, 1);
      std::sort(t.begin(), t.end());
      t.front() = 0;
      t.back() = 1;
      const BSplineCurve<double> truth(KnotVector::clamped_for_fit(order, n, t), test::random_points<double>(rng, n));
      std::vector<double> pts;
      for (double x : t) pts.push_back(truth.eval(x));
      const auto fit = fit_curve(pts, t, order, n);
      for (int i = 0; i < n; ++i) EXPECT_NEAR(fit.control_points()[i], truth.control_points()[i], 1e-9);
    }
  }
}

TEST(FitCurve, InterpolatesEndPointsAndMinimisesSquaredError) {
  test::Rng rng(43);
  std::vector<glm::dvec2> pts;
  for (int i = 0; i < 40; ++i) pts.push_back({std::cos(i * 0.1), std::sin(i * 0.13) + test::uniform(rng, -0.1, 0.1)});
  const auto t = parametrize(pts, Parametrization::Centripetal);
  const auto fit = fit_curve(pts, t, 4, 8);
  EXPECT_EQ(fit.control_points().front(), pts.front());  // exactly, by construction (P&T 9.4.1)
  EXPECT_EQ(fit.control_points().back(), pts.back());
  EXPECT_LE(test::norm_inf(fit.eval(0.0) - pts.front()), 1e-15);
  EXPECT_LE(test::norm_inf(fit.eval(1.0) - pts.back()), 1e-15);
  auto error = [&](const BSplineCurve<glm::dvec2>& c) {
    double e = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const glm::dvec2 d = c.eval(t[k]) - pts[k];
      e += glm::dot(d, d);
    }
    return e;
  };
  const double best = error(fit);
  for (int i = 1; i < 7; ++i)  // interior controls are free: any perturbation must increase the error
    for (int c = 0; c < 2; ++c)
      for (double eps : {1e-4, -1e-4}) {
        auto moved = fit;
        moved.control_points()[i][c] += eps;
        EXPECT_GT(error(moved), best) << "control " << i;
      }
}

TEST(FitSurface, RecoversSurfaceSampledFromItself) {
  test::Rng rng(44);
  for (int ou = 2; ou <= 4; ++ou)
    for (int ov = 1; ov <= 4; ++ov) {
      const KnotVector ku = test::random_knots(rng, ou, ou + 3, true, 1);
      const KnotVector kv = test::random_knots(rng, ov, std::max(ov, 2) + 2, true, std::max(1, ov - 1));
      const int cu = ku.control_count(), cv = kv.control_count();
      const BSplineSurface<glm::dvec3> truth(ku, kv, test::random_points<glm::dvec3>(rng, cu * cv));
      const auto tu = params_covering(rng, ku, 2), tv = params_covering(rng, kv, 3);
      const int pu = static_cast<int>(tu.size()), pv = static_cast<int>(tv.size());
      std::vector<glm::dvec3> grid;
      for (double v : tv)
        for (double u : tu) grid.push_back(truth.eval(u, v));
      const auto fit = fit_surface(grid, pu, pv, tu, tv, ku, kv);
      ASSERT_EQ(fit.control_points().size(), truth.control_points().size());
      for (std::size_t i = 0; i < truth.control_points().size(); ++i)
        EXPECT_LE(test::norm_inf(fit.control_points()[i] - truth.control_points()[i]), 1e-9);
      // Corners are interpolated.
      EXPECT_LE(test::norm_inf(fit.eval(1, 1) - grid.back()), 1e-14);
      // The order/count overload agrees with the knots it would choose.
      const auto fit2 = fit_surface(grid, pu, pv, tu, tv, ou, ov, cu, cv);
      EXPECT_EQ(fit2.knots(0).knots(), KnotVector::clamped_for_fit(ou, cu, tu).knots());
    }
}

TEST(Fitting, DegenerateInputThrowsClearly) {
  const std::vector<double> pts = {0, 1, 2}, t = {0, 0.5, 1};
  test::expect_invalid([&] { fit_curve(pts, t, 3, 5); }, "3 points for 5 control points");
  test::expect_invalid([&] { fit_curve(pts, {0, 1}, 2, 2); }, "3 points but 2 parameters");
  test::expect_invalid([&] { fit_curve(pts, t, 4, 3); }, "exceeds control count");
  test::expect_invalid([&] { fit_curve(pts, {0, 0.5, 0.9}, 2, 2); }, "parameters must run from");
  test::expect_invalid([&] { fit_curve(pts, {0, 0.7, 0.5}, 2, 2); }, "non-decreasing");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  test::expect_invalid([&] { fit_curve(std::vector<double>{0, nan, 2}, t, 2, 3); }, "point 1 is not finite");
  // Five points but all interior ones in one span of the given knots: the normal equations are singular.
  const KnotVector kv = KnotVector::clamped_uniform(2, 6);
  test::expect_invalid(
      [&] {
        fit_curve(std::vector<double>{0, 1, 2, 3, 4, 5}, {0, 0.01, 0.02, 0.03, 0.04, 1}, kv);
      },
      "singular");
  test::expect_invalid([&] { fit_curve(std::vector<double>{0, 1, 2}, t, KnotVector::uniform(2, 3)); }, "clamped");
  test::expect_invalid(
      [&] {
        fit_surface(std::vector<double>(6, 0.0), 2, 3, {0, 1}, {0, 0.5, 1}, 2, 2, 3, 2);
      },
      "degenerate input");
  test::expect_invalid(
      [&] {
        fit_surface(std::vector<double>(5, 0.0), 2, 3, {0, 1}, {0, 0.5, 1}, 2, 2, 2, 2);
      },
      "grid has 5 points");
}

}  // namespace
}  // namespace trispline::core
