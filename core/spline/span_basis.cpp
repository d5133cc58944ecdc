// SpanBasis: power-basis tables per span (Taylor coefficients from Piegl & Tiller A2.3), Horner evaluation.
#include "core/spline/span_basis.h"

#include <algorithm>
#include <cmath>

#include "core/spline/bspline_basis.h"

namespace trispline::core {

template <class Real>
SpanBasis<Real>::SpanBasis(const KnotVector& kv)
    : order_(kv.order()), uniform_(kv.has_uniform_spans()), period_(kv.period()) {
  const int p = kv.degree(), n = kv.control_count(), k1 = order_;
  const std::vector<double>& U = kv.knots();
  std::vector<double> ders(static_cast<std::size_t>(k1 * k1));
  for (int s = p; s < n; ++s) {
    if (U[s] == U[s + 1]) continue;
    const double h = U[s + 1] - U[s];
    basis_derivatives(kv, s, U[s], p, ders.data());
    begin_.push_back(static_cast<Real>(U[s]));
    inv_len_.push_back(static_cast<Real>(1.0 / h));
    first_.push_back(s - p);
    const std::size_t base = coef_.size();
    coef_.resize(base + static_cast<std::size_t>(k1 * k1));
    dcoef_.resize(base + static_cast<std::size_t>(k1 * k1), Real(0));
    double scale = 1.0;  // h^k / k!
    for (int k = 0; k <= p; ++k) {
      for (int r = 0; r < k1; ++r) coef_[base + k * k1 + r] = static_cast<Real>(ders[k * k1 + r] * scale);
      scale *= h / static_cast<double>(k + 1);
    }
    // d/dt Σ c_k x^k = Σ_{k≥1} k c_k x^{k−1} / h; from the double coefficients, then rounded once.
    scale = 1.0;  // h^(k−1) / (k−1)!  for derivative power k−1
    for (int k = 1; k <= p; ++k) {
      for (int r = 0; r < k1; ++r) dcoef_[base + (k - 1) * k1 + r] = static_cast<Real>(ders[k * k1 + r] * scale);
      scale *= h / static_cast<double>(k);
    }
  }
  span_count_ = static_cast<int>(first_.size());
  begin_.push_back(static_cast<Real>(kv.domain_max()));
  t0_ = static_cast<Real>(kv.domain_min());
  t1_ = static_cast<Real>(kv.domain_max());
  inv_h_ = static_cast<Real>(static_cast<double>(span_count_) / (kv.domain_max() - kv.domain_min()));
}

template <class Real>
int SpanBasis<Real>::locate(Real t, Real* x) const {
  if (period_ > 0) t -= std::floor(t);  // periodic: domain [0,1] is one period
  t = t >= t0_ ? t : t0_;               // also maps NaN to t0
  t = t <= t1_ ? t : t1_;
  int s;
  if (uniform_) {
    s = static_cast<int>((t - t0_) * inv_h_);
    s = std::min(std::max(s, 0), span_count_ - 1);
    // Rounding in (t − t0)·inv_h can land one span off next to a knot: correct against the stored boundaries.
    s -= (t < begin_[s]) ? 1 : 0;
    s += (s + 1 < span_count_ && t >= begin_[s + 1]) ? 1 : 0;
  } else {
    s = static_cast<int>(std::upper_bound(begin_.begin() + 1, begin_.end() - 1, t) - begin_.begin()) - 1;
  }
  *x = (t - begin_[s]) * inv_len_[s];
  return s;
}

template <class Real>
int SpanBasis<Real>::eval(Real t, Real* N, Real* dN) const {
  Real x;
  const int s = locate(t, &x);
  const int k1 = order_;
  const Real* c = &coef_[static_cast<std::size_t>(s) * k1 * k1];
  for (int r = 0; r < k1; ++r) N[r] = c[(k1 - 1) * k1 + r];
  for (int k = k1 - 2; k >= 0; --k)
    for (int r = 0; r < k1; ++r) N[r] = N[r] * x + c[k * k1 + r];
  if (dN) {
    const Real* d = &dcoef_[static_cast<std::size_t>(s) * k1 * k1];
    if (k1 == 1) {
      dN[0] = Real(0);
    } else {
      for (int r = 0; r < k1; ++r) dN[r] = d[(k1 - 2) * k1 + r];
      for (int k = k1 - 3; k >= 0; --k)
        for (int r = 0; r < k1; ++r) dN[r] = dN[r] * x + d[k * k1 + r];
    }
  }
  return first_[s];
}

template class SpanBasis<float>;
template class SpanBasis<double>;

}  // namespace trispline::core
