// core::ring_lattice (core/placement/ring_lattice.h): bad sizes are refused (radius within half the width, fewer
// control points than the order, orders outside 2..4); untwisted, the lattice is the one built before twist_deg
// existed, bit for bit; twisted (seed Fig. 4.6, a Möbius band at 180°), one period of u spans ring_twist_laps turns,
// the lattice is the twisted ring exactly at its control points' parameters, closes across the seam, turns over after
// one turn of a half twist (the bottom face one surface met from both sides) and keeps det J > 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/placement/ring_lattice.h"
#include "core/spline/bspline_basis.h"
#include "core/spline/knot_vector.h"

using namespace trispline;

namespace ring_lattice_test {

constexpr double kPi = 3.14159265358979323846;
// Coordinates are ~1 world unit: 1e-12 is rounding (a few thousand ulps) and nothing else.
constexpr double kRounding = 1e-12;

struct Ring {
  glm::dvec3 center{0.5, 0.1, -0.25};
  double radius = 1.2, width = 0.5, height = 0.3;
  glm::ivec3 controls{32, 2, 2}, order{4, 2, 2};
  double twist_deg = 180.0;
  core::TrivariateBSpline<glm::dvec3> build() const {
    return core::ring_lattice(center, radius, width, height, controls, order, twist_deg);
  }
};

// Parameter of control point i around the ring (the centre of its basis function's support).
double control_parameter(int i, int order, int n) { return (i - 0.5 * (order - 2)) / n; }

// The twisted ring itself: θ = 2π·laps·g round the ring, the cross-section point ((v − ½)·width, w·height) turned by
// φ = twist·laps·g about the centre line, outwards towards up.
glm::dvec3 twisted_ring_point(const Ring& r, double g, double v, double w) {
  const int laps = core::ring_twist_laps(r.twist_deg);
  const double theta = 2.0 * kPi * laps * g, phi = r.twist_deg * kPi / 180.0 * laps * g;
  const double x = (v - 0.5) * r.width, y = w * r.height;
  const double s = x * std::cos(phi) - y * std::sin(phi), t = x * std::sin(phi) + y * std::cos(phi);
  return r.center + glm::dvec3((r.radius + s) * std::cos(theta), t, (r.radius + s) * std::sin(theta));
}

// ring_lattice as it was before twist_deg (commit f8fcd8c), copied verbatim: the untwisted lattice must not move a bit.
core::TrivariateBSpline<glm::dvec3> ring_lattice_before_twist(const glm::dvec3& center, double radius, double width,
                                                              double height, const glm::ivec3& controls,
                                                              const glm::ivec3& order) {
  const double kTwoPi = 6.283185307179586476925286766559;
  const auto periodic_control_parameter = [](int i, int order, int period) {
    return (static_cast<double>(i) - 0.5 * (order - 2)) / period;
  };
  const auto periodic_circle_shrink = [&](const core::KnotVector& ku) {
    const int order = ku.order(), period = ku.period();
    const double g0 = periodic_control_parameter(0, order, period);
    const double t = g0 - std::floor(g0);
    const int span = ku.find_span(t);
    std::vector<double> N(static_cast<std::size_t>(order));
    core::basis_functions(ku, span, t, N.data());
    double r = 0.0;
    for (int k = 0; k < order; ++k) {
      const int i = span - order + 1 + k;
      r += N[k] * std::cos(kTwoPi * (periodic_control_parameter(i, order, period) - t));
    }
    return r;
  };
  core::KnotVector ku = core::KnotVector::periodic_uniform(order.x, controls.x);
  core::KnotVector kv = core::KnotVector::clamped_uniform(order.y, controls.y);
  core::KnotVector kw = core::KnotVector::clamped_uniform(order.z, controls.z);
  const double grow = 1.0 / periodic_circle_shrink(ku);
  const std::vector<double> gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> cps;
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i) {
        const double theta = kTwoPi * periodic_control_parameter(i, order.x, controls.x);
        const double r = (radius + (gv[j] - 0.5) * width) * grow;
        cps.emplace_back(center.x + r * std::cos(theta), center.y + gw[k] * height, center.z + r * std::sin(theta));
      }
  return core::TrivariateBSpline<glm::dvec3>(std::move(ku), std::move(kv), std::move(kw), std::move(cps));
}

TEST(RingLatticeFunction, RejectsBadSizes) {
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 0.2, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {3, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {5, 2, 2}), std::invalid_argument);
  EXPECT_NO_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}));
}

TEST(RingLatticeFunction, LapsAreTheTurnsAfterWhichTheTwistComesBack) {
  const std::vector<std::pair<double, int>> cases = {{0, 1},   {180, 2},  {-180, 2}, {90, 4},  {-90, 4}, {270, 4},
                                                     {360, 1}, {-360, 1}, {540, 2},  {630, 4}, {720, 1}, {-720, 1}};
  for (const auto& [twist, laps] : cases) {
    EXPECT_EQ(core::ring_twist_laps(twist), laps) << twist;
    EXPECT_EQ(std::fmod(laps * twist, 360.0), 0.0) << twist;  // the cross-section is back after `laps` turns
  }
  for (const double bad : {45.0, 1000.0, 810.0, -900.0, 180.5, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(core::ring_twist_laps(bad), std::invalid_argument) << bad;
}

TEST(RingLatticeFunction, TwistedRejectsBadTwistsCrossingRadiiAndTooFewControlPoints) {
  Ring r;
  EXPECT_NO_THROW(r.build());
  for (const double bad : {45.0, 1000.0}) {
    r.twist_deg = bad;
    EXPECT_THROW(r.build(), std::invalid_argument) << bad;
  }
  r = Ring{};
  r.radius = 0.38;  // > width/2 = 0.25 (fine untwisted), < hypot(0.25, 0.3) = 0.39: the turning corner crosses the axis
  EXPECT_THROW(r.build(), std::invalid_argument);
  r.twist_deg = 0.0;
  EXPECT_NO_THROW(r.build());
  r = Ring{};
  r.controls.x = 33;  // two turns of a half twist: not a multiple of 2
  EXPECT_THROW(r.build(), std::invalid_argument);
  r.twist_deg = 90.0;  // four turns
  r.controls.x = 8;    // a multiple of 4, but 2 per turn
  EXPECT_THROW(r.build(), std::invalid_argument);
  r.controls.x = 12;
  EXPECT_NO_THROW(r.build());
}

TEST(RingLatticeFunction, UntwistedIsTheLatticeBeforeTheTwistBitForBit) {
  struct Case {
    glm::dvec3 center;
    double radius, width, height;
    glm::ivec3 controls, order;
  };
  for (const Case& c :
       {Case{{0, 0, 0}, 1.4, 0.54, 0.69, {16, 2, 2}, {4, 2, 2}},
        Case{{0.5, 0.1, -0.25}, 1.2, 0.5, 0.3, {12, 2, 2}, {3, 2, 2}},
        Case{{-2, 3, 1}, 0.6, 0.2, 0.1, {16, 3, 4}, {4, 3, 2}}, Case{{0, 0, 0}, 1.0, 0.5, 0.1, {7, 2, 2}, {2, 2, 2}}}) {
    const auto want = ring_lattice_before_twist(c.center, c.radius, c.width, c.height, c.controls, c.order);
    const auto got = core::ring_lattice(c.center, c.radius, c.width, c.height, c.controls, c.order, 0.0);
    EXPECT_EQ(got.control_points(), want.control_points()) << c.controls.x << " controls, order " << c.order.x;
    EXPECT_EQ(got.knots(0).knots(), want.knots(0).knots());
    EXPECT_EQ(got.control_points(),
              core::ring_lattice(c.center, c.radius, c.width, c.height, c.controls, c.order).control_points());
  }
}

// At every control point's parameter (those next to the seam included) F is the twisted ring: the centre line passes
// through `radius` in the plane y = center.y, and the cross-section is turned rigidly by twist·laps·g. This is where
// the laps matter: the cross-section at g_i + 1 is the one at g_i only because laps·twist is a multiple of 360°.
TEST(RingLatticeFunction, TwistedIsTheTwistedRingAtTheControlParameters) {
  for (const double twist : {180.0, -180.0, 90.0, 360.0, 540.0})
    for (const glm::ivec3 order : {glm::ivec3(4, 2, 2), glm::ivec3(3, 2, 2), glm::ivec3(4, 3, 3)}) {
      Ring r;
      r.twist_deg = twist;
      r.order = order;
      r.controls = {48, order.y + 1, order.z + 1};  // a multiple of 1, 2 and 4 laps; 12 per turn at 4 laps
      const auto F = r.build();
      double worst = 0.0;
      for (int i = 0; i < r.controls.x; ++i) {
        const double g = control_parameter(i, order.x, r.controls.x);
        for (const double v : {0.0, 0.3, 0.5, 1.0})
          for (const double w : {0.0, 0.4, 1.0})
            worst = std::max(worst, glm::length(F.eval(glm::dvec3(g, v, w)) - twisted_ring_point(r, g, v, w)));
      }
      EXPECT_LT(worst, kRounding) << "twist " << twist << ", order " << order.x << order.y << order.z;
    }
}

// A half twist: F(u + 1) = F(u) (periodic), and one turn later (u + ½) every point is the first turn's turned over
// about the centre line — the bottom face w = 0 is one band met from both sides, ∂F/∂w pointing the other way.
TEST(RingLatticeFunction, HalfTwistTurnsOverAfterOneTurnAndClosesAfterTwo) {
  for (const double twist : {180.0, -180.0}) {
    Ring r;
    r.twist_deg = twist;
    const auto F = r.build();
    for (int a = 0; a < 64; ++a) {
      const double u = (a + 0.37) / 64.0;
      const glm::dvec3 centre = F.eval(glm::dvec3(u, 0.5, 0.0));
      EXPECT_LT(glm::length(F.eval(glm::dvec3(u + 1.0, 0.5, 0.0)) - centre), kRounding) << u;
      // One turn later: the same point of the band.
      EXPECT_LT(glm::length(F.eval(glm::dvec3(u + 0.5, 0.5, 0.0)) - centre), kRounding) << u;
      for (const double v : {0.0, 0.25, 1.0})
        for (const double w : {0.0, 0.5, 1.0}) {
          const glm::dvec3 here = F.eval(glm::dvec3(u, v, w)) - centre,
                           later = F.eval(glm::dvec3(u + 0.5, v, w)) - centre;
          EXPECT_LT(glm::length(later + here), kRounding) << u << " " << v << " " << w;
        }
      const glm::dvec3 up = F.eval_first(glm::dvec3(u, 0.5, 0.0)).d[2],
                       up_later = F.eval_first(glm::dvec3(u + 0.5, 0.5, 0.0)).d[2];
      EXPECT_LT(glm::dot(up, up_later), 0.0) << u;
      EXPECT_LT(glm::length(up + up_later), kRounding) << u;
      EXPECT_NEAR(glm::length(up), r.height, 1e-3 * r.height) << u;  // w still spans the height (ripple ~1e-4)
    }
  }
}

// det J > 0 everywhere, across the seam included: the twist is a rotation of the cross-section's plane. On the twisted
// ring det J = 2π·laps·(radius + s)·width·height with s ≥ −hypot(width/2, height); the lattice follows the ring up to
// the B-spline's ripple, so its minimum is that one within 10% (it is within 0.2% at 8 to 32 control points per turn).
TEST(RingLatticeFunction, TwistedKeepsDetJPositive) {
  for (const double twist : {180.0, -180.0, 90.0, 360.0}) {
    Ring r;
    r.twist_deg = twist;
    const int laps = core::ring_twist_laps(twist);
    const auto F = r.build();
    const double ring_min = 2.0 * kPi * laps * (r.radius - std::hypot(0.5 * r.width, r.height)) * r.width * r.height;
    double lo = INFINITY;
    for (int a = 0; a <= 96; ++a)
      for (int b = 0; b <= 4; ++b)
        for (int c = 0; c <= 4; ++c)
          lo = std::min(lo, core::jacobian_determinant(F, glm::dvec3(a / 96.0 - 0.005, b / 4.0, c / 4.0)));
    EXPECT_GT(lo, 0.9 * ring_min) << "twist " << twist;
  }
}

}  // namespace ring_lattice_test
