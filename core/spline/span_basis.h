// trispline::core::SpanBasis<Real> — the FFD fast path for B-spline basis functions (Real = float or double).
//
// Precomputed from a KnotVector: on every non-empty span [t_s, t_{s+1}) within the domain, each of the `order`
// non-zero basis functions is stored as a power-basis polynomial in the local coordinate x = (t − t_s)/(t_{s+1} − t_s)
// ∈ [0,1], so evaluation is span lookup + Horner with no division and no recurrence. Span lookup is O(1) (floor)
// when KnotVector::has_uniform_spans(), a binary search otherwise; both follow KnotVector::find_span's convention
// (t clamped to the domain, or wrapped t − ⌊t⌋ on a periodic knot vector; t == domain_max belongs to the last span;
// NaN maps to domain_min). On a periodic axis the returned first index is unwrapped: basis r uses control
// (first + r) mod period().
// Tables are contiguous, coefficient-major ([span][power][basis]) so the inner loops run over the `order` basis
// functions with unit stride and vectorise.
// Accuracy against basis_functions / basis_derivatives: ≤ 1e-12 (double), ≤ 1e-5 relative (float) (tests).
// Source: power-basis coefficients c_k = B^(k)(t_s)·h^k / k! from Piegl & Tiller A2.3 (Taylor expansion on a span).
#pragma once

#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core {

template <class Real>
class SpanBasis {
 public:
  explicit SpanBasis(const KnotVector& kv);

  int order() const { return order_; }
  int span_count() const { return span_count_; }  // number of non-empty spans in the domain
  bool uniform() const { return uniform_; }       // O(1) span lookup in use
  bool periodic() const { return period_ > 0; }   // parameters wrap, control indices are taken mod period()
  int period() const { return period_; }          // KnotVector::period(): 0 unless periodic
  Real domain_min() const { return t0_; }
  Real domain_max() const { return t1_; }
  Real inv_uniform_length() const { return inv_h_; }  // span_count / (domain_max − domain_min)

  // N[r] = B_{first+r}(t), dN[r] = B'_{first+r}(t) (per unit of t) for r in [0, order); returns first (the index of
  // the first non-zero basis function, = find_span(t) − order + 1). N must hold order() values; dN may be null.
  int eval(Real t, Real* N, Real* dN) const;

  // Slot of the non-empty span containing t (in [0, span_count())) and the local coordinate x ∈ [0,1] (for
  // callers that evaluate several derivative orders themselves).
  int locate(Real t, Real* x) const;

  // Raw tables for vectorised/GPU consumers: coefficients(slot)[k·order + r] = coefficient of x^k of basis r on the
  // span; first_index(slot) = index of basis r = 0.
  const Real* coefficients(int slot) const { return &coef_[static_cast<std::size_t>(slot) * order_ * order_]; }
  // Same layout for dB/dt (per unit of t); power k = order − 1 is 0.
  const Real* derivative_coefficients(int slot) const {
    return &dcoef_[static_cast<std::size_t>(slot) * order_ * order_];
  }
  int first_index(int slot) const { return first_[slot]; }
  const std::vector<Real>& span_begins() const { return begin_; }         // #S + 1 (last = domain_max)
  const std::vector<Real>& inv_span_lengths() const { return inv_len_; }  // #S, 1 / span length
  const std::vector<int>& first_indices() const { return first_; }        // #S
  const std::vector<Real>& coefficient_table() const { return coef_; }    // #S·order·order, [slot][k][r]

 private:
  int order_ = 0;
  int span_count_ = 0;
  bool uniform_ = false;
  int period_ = 0;
  Real t0_ = 0, t1_ = 0, inv_h_ = 0;  // domain and 1 / uniform span length
  std::vector<Real> begin_;           // #S+1: span boundaries (end of the last span at [S])
  std::vector<Real> inv_len_;         // #S: 1 / span length
  std::vector<int> first_;            // #S: first basis index
  std::vector<Real> coef_;            // #S·order·order: [slot][k][r] coefficient of x^k
  std::vector<Real> dcoef_;           // #S·order·order: [slot][k][r] coefficient of x^k of dB/dt (per unit t)
};

extern template class SpanBasis<float>;
extern template class SpanBasis<double>;

}  // namespace trispline::core
