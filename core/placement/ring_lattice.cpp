// The ring lattice. See ring_lattice.h. Source: seed §4.5 (Fig. 4.5; Fig. 4.6 for the twist); periodic knot vectors,
// Piegl & Tiller §12.2.
//
// The twist (seed Fig. 4.6: ants walking round a Möbius band).
//   Control point i has the parameter g_i (the centre of its basis function's support, below) and sits at the angle
//   θ_i = 2π·laps·g_i round the ring; its cross-section is turned about the centre line by φ_i = twist·laps·g_i, i.e.
//   twist per turn. A cross-section point x = (v − ½)·width across and y = w·height up goes to
//     s = x cos φ − y sin φ  outwards,   t = x sin φ + y cos φ  up          (a rotation of the (outwards, up) plane).
//   Laps: a periodic knot vector uses control point i + n as i (n = controls.x) and g_{i+n} = g_i + 1, so the lattice
//   closes only if one period brings θ and φ back: 2π·laps always does, laps·twist must be a multiple of 360°. Hence
//   laps = the smallest integer ≥ 1 with that property (ring_twist_laps), and one period of u is `laps` turns; the
//   twist is limited to multiples of 90° (laps 1, 2 or 4), enough for the Möbius band (180°) and its relatives.
//   The axis: the cross-section turns about its point v = ½, w = 0, on the bottom face where a placed object's feet
//   are. The bottom face is then the band itself: with a half twist, the second turn's bottom face is the first turn's
//   turned over (x → −x) with w pointing the other way, so an object walks one turn on top of the band and the next
//   upside down beneath the same surface, as Escher's ants. When n is a multiple of laps (required below), turn k's
//   control points are turn 0's with their cross-sections turned by k·twist, so the two sides are one surface exactly:
//   F(u + ½, v, w) − c(u) = −(F(u, v, w) − c(u)) for the centre line c(u) = F(u, ½, 0). Other twists: 360° closes in
//   one turn (a full twist); ±90° needs four turns whose volumes overlap where the turned cross-sections do (F is then
//   not one-to-one, though det J stays positive) — allowed, an effect rather than a band.
//   Orientation: the twist is a rotation of the (outwards, up) plane, so det[∂F/∂u, ∂F/∂v, ∂F/∂w] keeps the untwisted
//   sign — positive while every cross-section point stays on the outer side of the ring's axis, which the turning
//   cross-section only does if radius > hypot(width/2, height) (its farthest corner from the axis of the turn).
//
// Compensation: a uniform B-spline over control points on a circle lies inside the circle, and a turning
// cross-section is shrunk and sheared likewise. At g_i the non-zero basis functions are symmetric weights c_k of the
// neighbours i + k (⅙ ⅔ ⅙ for order 4, ⅛ ¾ ⅛ for order 3, 1 for order 2), which sit δθ_k = k·2π·laps/n further round
// and are turned δφ_k = k·twist·laps/n further. Sums over them (odd terms vanish by symmetry):
//   S_θ = Σ c_k cos δθ_k,  S_φ = Σ c_k cos δφ_k,  D = Σ c_k cos δθ_k cos δφ_k,  Q = Σ c_k sin δθ_k sin δφ_k.
// With control points
//   P_i = center + grow·(radius + κ·s_i)·e_r(θ_i) + σ·t_i·e_θ(θ_i) + β·t_i·e_y
// (e_r outwards, e_θ along the ring, e_y up), F(g_i, v, w) has, in control i's frame,
//   outwards  radius·grow·S_θ + s_i·(grow·κ·D − σ·Q),   along  t_i·(σ·D − grow·κ·Q),   up  β·S_φ·t_i.
// grow = 1/S_θ (the centre line s = t = 0 passes through `radius`: the untwisted ring's rule, with the angle step
// laps·2π/n), grow·κ = D/(D² − Q²), σ = Q/(D² − Q²) and β = 1/S_φ make F(g_i, v, w) = center + (radius + s_i)·e_r +
// t_i·e_y exactly: at the control points' parameters the lattice is the twisted ring, the cross-section turned rigidly
// in the plane across the ring (D² − Q² = (D − Q)(D + Q) ≥ 1/9 for orders ≤ 4: never singular). Between them the
// usual B-spline ripple remains (the centre line within ~1e-4·radius at 16 control points per turn, cubic). Untwisted,
// δφ = 0 gives κ = β = 1 and σ = 0, which the code takes literally: the lattice is the untwisted one bit for bit.
#include "core/placement/ring_lattice.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spline/bspline_basis.h"
#include "core/spline/knot_vector.h"

namespace trispline::core {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kDegree = 0.017453292519943295769236907684886;  // π/180

// Parameter of control point i on a periodic uniform axis: the centre of its basis function's support,
// g_i = (i − (order − 2)/2) / period (mod 1).
double periodic_control_parameter(int i, int order, int period) {
  return (static_cast<double>(i) - 0.5 * (order - 2)) / period;
}

// The factors of the compensation above: P_i = center + grow·(radius + κ·s)·e_r + σ·t·e_θ + β·t·e_y.
struct RingCompensation {
  double grow = 1.0, kappa = 1.0, sigma = 0.0, beta = 1.0;
};

// `turn` = 2π·laps (radians of θ per unit of u), `twist` = twist·laps (radians of φ per unit of u).
RingCompensation periodic_ring_compensation(const KnotVector& ku, double turn, double twist) {
  const int order = ku.order(), period = ku.period();
  const double g0 = periodic_control_parameter(0, order, period);
  const double t = g0 - std::floor(g0);
  const int span = ku.find_span(t);
  std::vector<double> N(static_cast<std::size_t>(order));
  basis_functions(ku, span, t, N.data());
  double s_theta = 0.0, s_phi = 0.0, d = 0.0, q = 0.0;
  for (int k = 0; k < order; ++k) {
    const int i = span - order + 1 + k;  // unwrapped control index; its parameter is periodic too
    const double dg = periodic_control_parameter(i, order, period) - t;
    s_theta += N[k] * std::cos(turn * dg);
    s_phi += N[k] * std::cos(twist * dg);
    d += N[k] * std::cos(turn * dg) * std::cos(twist * dg);
    q += N[k] * std::sin(turn * dg) * std::sin(twist * dg);
  }
  RingCompensation c;
  c.grow = 1.0 / s_theta;
  if (twist != 0.0) {
    const double det = d * d - q * q;
    c.kappa = d * s_theta / det;
    c.sigma = q / det;
    c.beta = 1.0 / s_phi;
  }
  return c;
}
}  // namespace

int ring_twist_laps(double twist_deg) {
  if (!(std::abs(twist_deg) <= 720.0) || std::fmod(twist_deg, 90.0) != 0.0)
    throw std::invalid_argument(
        "ring lattice: twist_deg must be a multiple of 90 in [-720, 720] (so that the lattice "
        "closes after 1, 2 or 4 turns), got " +
        std::to_string(twist_deg));
  const int quarters = static_cast<int>(std::lround(twist_deg / 90.0));
  int laps = 1;
  while ((laps * quarters) % 4 != 0) ++laps;  // laps·twist ≡ 0 (mod 360°): 1, 2 or 4
  return laps;
}

TrivariateBSpline<glm::dvec3> ring_lattice(const glm::dvec3& center, double radius, double width, double height,
                                           const glm::ivec3& controls, const glm::ivec3& order, double twist_deg) {
  if (!(radius > 0.0) || !(width > 0.0) || !(height > 0.0) || !std::isfinite(radius + width + height))
    throw std::invalid_argument("ring lattice: radius, width and height must be positive and finite");
  if (radius <= 0.5 * width)
    throw std::invalid_argument("ring lattice: radius " + std::to_string(radius) + " must exceed half the width (" +
                                std::to_string(0.5 * width) + ") or the inner edge crosses the ring's axis");
  for (int a = 0; a < 3; ++a)
    if (order[a] < 2 || order[a] > 4)
      throw std::invalid_argument("ring lattice: orders must be 2..4 (degree 1..3), got " + std::to_string(order[a]));
  if (controls.x < order.x)
    throw std::invalid_argument("ring lattice: need at least order (" + std::to_string(order.x) +
                                ") control points around the ring, got " + std::to_string(controls.x));
  const int laps = ring_twist_laps(twist_deg);
  const bool twisted = twist_deg != 0.0;
  if (twisted) {
    if (radius <= std::hypot(0.5 * width, height))
      throw std::invalid_argument(
          "ring lattice: radius " + std::to_string(radius) + " must exceed hypot(width / 2, height) = " +
          std::to_string(std::hypot(0.5 * width, height)) + " or the turning cross-section crosses the ring's axis");
    if (controls.x % laps != 0 || controls.x < 3 * laps)
      throw std::invalid_argument("ring lattice: a twist of " + std::to_string(twist_deg) + " degrees spans " +
                                  std::to_string(laps) + " turns: the control points around (" +
                                  std::to_string(controls.x) + ") must be a multiple of " + std::to_string(laps) +
                                  ", at least 3 per turn");
  }
  KnotVector ku = KnotVector::periodic_uniform(order.x, controls.x);
  KnotVector kv = KnotVector::clamped_uniform(order.y, controls.y);  // throws if controls < order
  KnotVector kw = KnotVector::clamped_uniform(order.z, controls.z);
  const double turn = kTwoPi * laps;                                // θ per unit of u
  const double twist = twisted ? twist_deg * kDegree * laps : 0.0;  // φ per unit of u
  const RingCompensation comp = periodic_ring_compensation(ku, turn, twist);
  const std::vector<double> gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> cps;
  cps.reserve(static_cast<std::size_t>(controls.x) * controls.y * controls.z);
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i) {
        const double g = periodic_control_parameter(i, order.x, controls.x);
        const double theta = turn * g;
        const double x = (gv[j] - 0.5) * width, y = gw[k] * height;
        // θ from +x towards +z (clockwise seen from +y), v outwards, w up: det[∂F/∂u, ∂F/∂v, ∂F/∂w] > 0.
        if (!twisted) {
          const double r = (radius + x) * comp.grow;
          cps.emplace_back(center.x + r * std::cos(theta), center.y + y, center.z + r * std::sin(theta));
          continue;
        }
        const double phi = twist * g;
        const double s = x * std::cos(phi) - y * std::sin(phi), t = x * std::sin(phi) + y * std::cos(phi);
        const double r = (radius + comp.kappa * s) * comp.grow, along = comp.sigma * t;
        const double c = std::cos(theta), sn = std::sin(theta);
        cps.emplace_back(center.x + r * c - along * sn, center.y + comp.beta * t, center.z + r * sn + along * c);
      }
  return TrivariateBSpline<glm::dvec3>(std::move(ku), std::move(kv), std::move(kw), std::move(cps));
}

}  // namespace trispline::core
