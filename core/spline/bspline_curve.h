// trispline::core::BSplineCurve<T> — C(t) = Σ_i P_i B_i(t), T = double (scalar), glm::dvec2 or glm::dvec3.
// Source: Piegl & Tiller ch. 3 (evaluation A3.1/A3.2), ch. 5 (knot insertion A5.1, Bézier decomposition A5.6).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core {

template <class T>
class BSplineCurve {
 public:
  // control_points: #n (n = knots.control_count()). Throws std::invalid_argument on count mismatch or
  // non-finite control points.
  BSplineCurve(KnotVector knots, std::vector<T> control_points);

  const KnotVector& knots() const { return knots_; }
  int order() const { return knots_.order(); }
  const std::vector<T>& control_points() const { return cps_; }
  std::vector<T>& control_points() { return cps_; }

  T eval(double t) const;  // t clamped to the domain; throws std::invalid_argument if NaN
  // out[d] = d-th derivative at t, d in [0, n_deriv]; out.size() == n_deriv + 1.
  std::vector<T> derivatives(double t, int n_deriv) const;

  // Boehm knot insertion of t, `times` times (total multiplicity capped at order, i.e. C^-1). Leaves the curve
  // unchanged as a function. Throws std::invalid_argument if t is outside the domain.
  void insert_knot(double t, int times = 1);
  // Splits into Bézier pieces (one per non-empty span), each with a clamped knot vector on its own span.
  std::vector<BSplineCurve<T>> bezier_pieces() const;
  // The same curve with every domain knot (ends included) at multiplicity = order and knots outside the domain
  // dropped: clamped, span s is the Bézier piece with controls [s·order, (s+1)·order).
  BSplineCurve<T> bezier_extracted() const;

 private:
  KnotVector knots_;
  std::vector<T> cps_;
};

extern template class BSplineCurve<double>;
extern template class BSplineCurve<glm::dvec2>;
extern template class BSplineCurve<glm::dvec3>;

}  // namespace trispline::core
