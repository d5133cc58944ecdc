// B-spline basis functions and their derivatives (Cox–de Boor recurrence).
// Source: Piegl & Tiller A2.2 (BasisFuns) and A2.3 (DersBasisFuns).
#pragma once

#include "core/spline/knot_vector.h"

namespace trispline::core {

// N[r] = B_{span-order+1+r}(t) for r in [0, order): the `order` non-zero basis functions at t in span `span`
// (from KnotVector::find_span). N must hold order() doubles. Sums to 1 (partition of unity).
void basis_functions(const KnotVector& kv, int span, double t, double* N);

// ders[d * order + r] = d-th derivative of B_{span-order+1+r} at t, for d in [0, n_deriv] (derivatives above the
// degree are 0). ders must hold (n_deriv + 1) * order doubles.
void basis_derivatives(const KnotVector& kv, int span, double t, int n_deriv, double* ders);

// basis_derivatives with n_deriv = 1, the hot path of every Jacobian (FFD normals, seed §4.3): N[r] values and
// dN[r] first derivatives, r in [0, order); N and dN must hold order() doubles each. The same arithmetic as A2.3
// restricted to k = 1 (N'_{i,p} = p·(N_{i,p−1}/(u_{i+p} − u_i) − N_{i+1,p−1}/(u_{i+p+1} − u_{i+1}))), so the results
// are bit-identical to basis_derivatives(kv, span, t, 1, ·), without its (p+1)² table.
void basis_first_derivatives(const KnotVector& kv, int span, double t, double* N, double* dN);

namespace detail {
// A2.3's k = 1 row (shared with the fixed-order FFD evaluator so both stay bit-identical): dN[r] for r in [0, p] from
// the degree-(p − 1) values prev[0..p) and the last Cox–de Boor step's knot differences diff[0..p), p ≥ 1.
inline void first_derivative_row(int p, const double* prev, const double* diff, double* dN) {
  const double f = p;
  for (int r = 0; r <= p; ++r) {
    double d = 0.0;
    if (r >= 1) d = (1.0 / diff[r - 1]) * prev[r - 1];
    if (r <= p - 1) d += (-1.0 / diff[r]) * prev[r];
    dN[r] = d * f;
  }
}
}  // namespace detail

}  // namespace trispline::core
