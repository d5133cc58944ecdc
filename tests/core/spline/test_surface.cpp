// BSplineSurface: tensor-product evaluation, partials vs central differences, normal, knot insertion and Bézier
// extraction leave the surface unchanged.
#include <limits>

#include "core/spline/bspline_curve.h"
#include "core/spline/bspline_surface.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

using Surface3 = BSplineSurface<glm::dvec3>;

Surface3 random_surface(test::Rng& rng, int ou, int ov, bool clamped) {
  const int nu = test::uniform_int(rng, ou, ou + 4), nv = test::uniform_int(rng, ov, ov + 4);
  return Surface3(test::random_knots(rng, ou, nu, clamped, ou), test::random_knots(rng, ov, nv, !clamped, ov),
                  test::random_points<glm::dvec3>(rng, static_cast<std::size_t>(nu * nv)));
}

double max_difference(test::Rng& rng, const Surface3& a, const Surface3& b) {
  double m = 0;
  const auto us = test::sample_params(rng, a.knots(0), 15), vs = test::sample_params(rng, a.knots(1), 15);
  for (double u : us)
    for (double v : vs) m = std::max(m, test::norm_inf(a.eval(u, v) - b.eval(u, v)));
  return m;
}

TEST(Surface, IsoCurveMatchesCurveEvaluation) {
  // Fixing v, S(·, v) is the curve whose controls are Σ_j P_ij B_j(v): compare against BSplineCurve.
  test::Rng rng(21);
  const Surface3 s = random_surface(rng, 3, 4, true);
  const double v = 0.37;
  const int nu = s.control_count(0), nv = s.control_count(1);
  std::vector<glm::dvec3> column(nv), row(nu);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) column[j] = s.control_point(i, j);
    row[i] = BSplineCurve<glm::dvec3>(s.knots(1), column).eval(v);
  }
  const BSplineCurve<glm::dvec3> iso(s.knots(0), row);
  for (double u : {0.0, 0.1, 0.5, 0.77, 1.0}) EXPECT_LE(test::norm_inf(iso.eval(u) - s.eval(u, v)), 1e-14);
}

TEST(Surface, PartialsMatchCentralDifferences) {
  test::Rng rng(22);
  const double h = 1e-6;
  for (int ou = 1; ou <= 5; ++ou)
    for (int ov = 1; ov <= 5; ++ov) {
      const Surface3 s = random_surface(rng, ou, ov, (ou + ov) % 2 == 0);
      for (int k = 0; k < 10; ++k) {
        const double u = test::param_away_from_knots(rng, s.knots(0), 1e-3);
        const double v = test::param_away_from_knots(rng, s.knots(1), 1e-3);
        const auto f = s.eval_first(u, v);
        const auto g = s.eval_second(u, v);
        EXPECT_LE(test::norm_inf(f.value - s.eval(u, v)), 1e-14);
        EXPECT_LE(test::norm_inf(g.du - f.du) + test::norm_inf(g.dv - f.dv), 1e-14);
        auto near = [](const glm::dvec3& an, const glm::dvec3& fd) {
          return test::norm_inf(an - fd) <= 1e-5 * (1 + test::norm_inf(an));
        };
        EXPECT_TRUE(near(f.du, (s.eval(u + h, v) - s.eval(u - h, v)) / (2 * h)));
        EXPECT_TRUE(near(f.dv, (s.eval(u, v + h) - s.eval(u, v - h)) / (2 * h)));
        const auto up = s.eval_first(u + h, v), um = s.eval_first(u - h, v);
        const auto vp = s.eval_first(u, v + h), vm = s.eval_first(u, v - h);
        EXPECT_TRUE(near(g.duu, (up.du - um.du) / (2 * h))) << ou << ov;
        EXPECT_TRUE(near(g.duv, (vp.du - vm.du) / (2 * h))) << ou << ov;
        EXPECT_TRUE(near(g.duv, (up.dv - um.dv) / (2 * h))) << ou << ov;
        EXPECT_TRUE(near(g.dvv, (vp.dv - vm.dv) / (2 * h))) << ou << ov;
      }
    }
}

TEST(Surface, NormalOfPlane) {
  // Bilinear patch in the xz-plane with u along x and v along -z: du × dv = (1,0,0) × (0,0,-1) = (0,1,0).
  const Surface3 s(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                   {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}, {1, 0, -1}});
  const glm::dvec3 n = s.normal(0.3, 0.6);
  EXPECT_NEAR(n.x, 0.0, 1e-15);
  EXPECT_NEAR(n.y, 1.0, 1e-15);
  EXPECT_NEAR(n.z, 0.0, 1e-15);
  const Surface3 flat(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                      {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}});
  EXPECT_EQ(flat.normal(0.5, 0.5), glm::dvec3(0.0));
}

TEST(Surface, KnotInsertionLeavesSurfaceUnchanged) {
  test::Rng rng(23);
  for (int ou = 1; ou <= 5; ++ou)
    for (int ov = 1; ov <= 5; ++ov) {
      const Surface3 original = random_surface(rng, ou, ov, ou % 2 == 0);
      Surface3 s = original;
      for (int axis = 0; axis < 2; ++axis) {
        const KnotVector& kv = original.knots(axis);
        s.insert_knot(axis, test::uniform(rng, kv.domain_min(), kv.domain_max()), 1);
        s.insert_knot(axis, kv[test::uniform_int(rng, kv.order() - 1, kv.control_count())], kv.order());
      }
      EXPECT_EQ(s.control_points().size(),
                static_cast<std::size_t>(s.control_count(0)) * static_cast<std::size_t>(s.control_count(1)));
      EXPECT_LE(max_difference(rng, original, s), 1e-12) << ou << " " << ov;
    }
}

TEST(Surface, BezierExtractionLeavesSurfaceUnchanged) {
  test::Rng rng(24);
  for (int ou = 1; ou <= 4; ++ou)
    for (int ov = 1; ov <= 4; ++ov) {
      const Surface3 s = random_surface(rng, ou, ov, ov % 2 == 0);
      const Surface3 e = s.bezier_extracted();
      EXPECT_TRUE(e.knots(0).is_clamped());
      EXPECT_TRUE(e.knots(1).is_clamped());
      for (int axis = 0; axis < 2; ++axis)
        for (double k : e.knots(axis).knots()) EXPECT_EQ(e.knots(axis).multiplicity(k), e.knots(axis).order());
      EXPECT_LE(max_difference(rng, s, e), 1e-12);
    }
}

TEST(Surface, InvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const KnotVector k = KnotVector::clamped_uniform(2, 2);
  test::expect_invalid([&] { BSplineSurface<double>(k, k, {1, 2, 3}); }, "wrong control point count");
  test::expect_invalid([&] { BSplineSurface<double>(k, k, {1, 2, nan, 4}); }, "control point 2 is not finite");
  BSplineSurface<double> s(k, k, {1, 2, 3, 4});
  test::expect_invalid([&] { s.insert_knot(2, 0.5); }, "axis");
  test::expect_invalid([&] { s.eval(0.5, nan); }, "NaN");
  EXPECT_THROW(s.normal(0.5, 0.5), std::logic_error);
}

}  // namespace
}  // namespace trispline::core
