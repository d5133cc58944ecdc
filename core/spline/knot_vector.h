// trispline::core::KnotVector — a validated, non-decreasing knot sequence with its order.
//
// Conventions (used by every spline API in trispline):
//   order      = degree + 1 (an order-4 B-spline is cubic).
//   n          = control_count(); knots().size() == n + order.
//   domain     = [knots[order-1], knots[n]]. Clamped ("open end") vectors have end knots of multiplicity = order
//                and, as built by the factories below, domain [0,1].
//   periodic   = closed (only from periodic_uniform): uniform knots, domain [0,1] = one period; a spline stores
//                period() control points along the axis and uses control index i mod period(); parameters wrap
//                (t − ⌊t⌋) instead of being clamped (seed Fig. 4.5: ring-shaped lattices without a seam).
// Errors: every constructor/factory throws std::invalid_argument with a message naming the problem
// (order < 1, order > control count, non-monotone or non-finite knots, empty domain).
// Source: Piegl & Tiller, The NURBS Book (2nd ed.), ch. 2.
#pragma once

#include <string>
#include <vector>

namespace trispline::core {

class KnotVector {
 public:
  // Explicit knots. Throws std::invalid_argument (see header comment).
  KnotVector(int order, std::vector<double> knots);

  // Clamped (open-end) knot vector on [0,1] with uniformly spaced interior knots: the FFD default (seed Eq. 2.1).
  static KnotVector clamped_uniform(int order, int control_count);
  // Floating uniform knot vector t_i = i (before normalisation) with domain rescaled to [0,1].
  static KnotVector uniform(int order, int control_count);
  // Periodic (closed) uniform knot vector of one period on [0,1] (seed Fig. 4.5): t_i = (i − p)/period for
  // i = 0 … period + 2p (p = order − 1), so control_count() = period + p (the unwrapped count: basis i uses control
  // i mod period) and there are `period` spans of length 1/period. The function is C^(p−1) everywhere, across the
  // seam t = 0 ≡ 1 included. Throws std::invalid_argument if order < 1 or period < 1.
  static KnotVector periodic_uniform(int order, int period);
  // Clamped knot vector on [0,1] whose interior knots are placed by averaging parameters (Piegl & Tiller Eq. 9.69),
  // the right choice for least-squares fitting with `control_count` controls to points at `params` (sorted, [0,1]).
  // With #params == control_count (interpolation) it uses knot averaging (Eq. 9.8; midpoints for order 1).
  // Throws std::invalid_argument if #params < control_count or params are unsorted / non-finite.
  static KnotVector clamped_for_fit(int order, int control_count, const std::vector<double>& params);

  int order() const { return order_; }
  int degree() const { return order_ - 1; }
  int control_count() const { return static_cast<int>(knots_.size()) - order_; }
  const std::vector<double>& knots() const { return knots_; }
  double operator[](int i) const { return knots_[i]; }
  double domain_min() const { return knots_[order_ - 1]; }
  double domain_max() const { return knots_[control_count()]; }
  bool is_periodic() const { return period_ > 0; }
  // Distinct control points along a periodic axis (control_count() − degree()); 0 when not periodic.
  int period() const { return period_; }
  // Control points a spline stores along this axis: period() when periodic, control_count() otherwise.
  int stored_control_count() const { return period_ > 0 ? period_ : control_count(); }
  // t mapped into the domain: wrapped (t − ⌊t⌋, the domain is [0,1]) when periodic, clamped otherwise. NaN stays NaN.
  double wrap_or_clamp(double t) const;

  // Span index s with knots[s] <= t < knots[s+1], s in [order-1, n-1]; t is first mapped by wrap_or_clamp and
  // t == domain_max maps to the last non-empty span (Piegl & Tiller A2.1). Throws std::invalid_argument on NaN.
  int find_span(double t) const;
  // Number of knots equal to t (exact comparison).
  int multiplicity(double t) const;
  // Greville abscissae: xi_i = (t_{i+1} + ... + t_{i+order-1}) / (order-1), #n; for order 1 the span midpoints.
  std::vector<double> greville() const;
  // True when the end knots have multiplicity = order (open end condition). False for periodic vectors.
  bool is_clamped() const;
  // True when all distinct interior spans have the same length (within 1e-12 of the domain length).
  bool has_uniform_spans() const;

 private:
  int order_ = 0;
  int period_ = 0;  // > 0 only for periodic_uniform
  std::vector<double> knots_;
};

}  // namespace trispline::core
