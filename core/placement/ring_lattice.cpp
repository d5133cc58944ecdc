// The ring lattice. See ring_lattice.h. Source: seed §4.5 (Fig. 4.5); periodic knot vectors, Piegl & Tiller §12.2.
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

// Parameter of control point i on a periodic uniform axis: the centre of its basis function's support,
// g_i = (i − (order − 2)/2) / period (mod 1).
double periodic_control_parameter(int i, int order, int period) {
  return (static_cast<double>(i) - 0.5 * (order - 2)) / period;
}

// Radius of the periodic uniform B-spline curve whose control polygon lies on the unit circle, at the parameter of a
// control point: Σ_r N_r(g_0)·cos(2π(g_{first+r} − g_0)). The control circle is scaled by its inverse.
double periodic_circle_shrink(const KnotVector& ku) {
  const int order = ku.order(), period = ku.period();
  const double g0 = periodic_control_parameter(0, order, period);
  const double t = g0 - std::floor(g0);
  const int span = ku.find_span(t);
  std::vector<double> N(static_cast<std::size_t>(order));
  basis_functions(ku, span, t, N.data());
  double r = 0.0;
  for (int k = 0; k < order; ++k) {
    const int i = span - order + 1 + k;  // unwrapped control index; its parameter is periodic too
    r += N[k] * std::cos(kTwoPi * (periodic_control_parameter(i, order, period) - t));
  }
  return r;
}
}  // namespace

TrivariateBSpline<glm::dvec3> ring_lattice(const glm::dvec3& center, double radius, double width, double height,
                                           const glm::ivec3& controls, const glm::ivec3& order) {
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
  KnotVector ku = KnotVector::periodic_uniform(order.x, controls.x);
  KnotVector kv = KnotVector::clamped_uniform(order.y, controls.y);  // throws if controls < order
  KnotVector kw = KnotVector::clamped_uniform(order.z, controls.z);
  const double grow = 1.0 / periodic_circle_shrink(ku);
  const std::vector<double> gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> cps;
  cps.reserve(static_cast<std::size_t>(controls.x) * controls.y * controls.z);
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i) {
        const double theta = kTwoPi * periodic_control_parameter(i, order.x, controls.x);
        const double r = (radius + (gv[j] - 0.5) * width) * grow;
        // θ from +x towards +z (clockwise seen from +y), v outwards, w up: det[∂F/∂u, ∂F/∂v, ∂F/∂w] > 0.
        cps.emplace_back(center.x + r * std::cos(theta), center.y + gw[k] * height, center.z + r * std::sin(theta));
      }
  return TrivariateBSpline<glm::dvec3>(std::move(ku), std::move(kv), std::move(kw), std::move(cps));
}

}  // namespace trispline::core
