// Boehm knot insertion and Bézier refinement along one axis of a tensor-product control array (internal).
// The control array is viewed as cps[a + inner·(i + n·b)] (see control_net.h); every (a, b) line is refined with
// the same knot-only coefficients, so curves, surfaces and trivariates share this one implementation.
// Source: Boehm 1980; Piegl & Tiller Eq. 5.10–5.15 (A5.1, one knot at a time), A5.3 (surfaces, per axis).
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core::detail {

template <class T>
struct AxisRefinement {
  KnotVector knots;
  std::vector<T> cps;
};

// Inserts t into kv `times` times, capped so that its multiplicity does not exceed order (C^-1). The function is
// unchanged. Throws std::invalid_argument if t is non-finite or outside [domain_min, domain_max], or times < 0.
template <class T>
AxisRefinement<T> insert_knot_axis(const KnotVector& kv, const std::vector<T>& cps, std::size_t inner,
                                   std::size_t outer, double t, int times, const char* who) {
  if (!std::isfinite(t) || t < kv.domain_min() || t > kv.domain_max())
    throw std::invalid_argument(std::string(who) + ": knot " + std::to_string(t) + " is outside the domain [" +
                                std::to_string(kv.domain_min()) + ", " + std::to_string(kv.domain_max()) + "]");
  if (times < 0) throw std::invalid_argument(std::string(who) + ": times must be >= 0, got " + std::to_string(times));
  const int order = kv.order(), p = kv.degree();
  const int r = std::min(times, order - kv.multiplicity(t));
  std::vector<double> U = kv.knots();
  std::vector<T> P = cps;
  int n = kv.control_count();
  std::vector<double> alpha(static_cast<std::size_t>(order));
  for (int pass = 0; pass < r; ++pass) {
    // Span k with U[k] <= t <= U[k+1], U[k] < U[k+1] (t == domain_max uses the last non-empty span).
    int k = static_cast<int>(std::upper_bound(U.begin() + p, U.begin() + n + 1, t) - U.begin()) - 1;
    if (k >= n) k = n - 1;
    while (U[k] == U[k + 1]) --k;
    for (int i = k - p + 1; i <= k; ++i) alpha[i - (k - p + 1)] = (t - U[i]) / (U[i + p] - U[i]);
    std::vector<T> Q(inner * outer * static_cast<std::size_t>(n + 1));
    for (std::size_t b = 0; b < outer; ++b) {
      for (std::size_t a = 0; a < inner; ++a) {
        auto src = [&](int i) -> const T& { return P[a + inner * (static_cast<std::size_t>(i) + n * b)]; };
        auto dst = [&](int i) -> T& { return Q[a + inner * (static_cast<std::size_t>(i) + (n + 1) * b)]; };
        for (int i = 0; i <= k - p; ++i) dst(i) = src(i);
        for (int i = k - p + 1; i <= k; ++i) {
          const double al = alpha[i - (k - p + 1)];
          dst(i) = src(i) * al + src(i - 1) * (1.0 - al);
        }
        for (int i = k + 1; i <= n; ++i) dst(i) = src(i - 1);
      }
    }
    U.insert(U.begin() + k + 1, t);
    P = std::move(Q);
    ++n;
  }
  return {KnotVector(order, std::move(U)), std::move(P)};
}

// Raises every distinct knot in the domain (ends included) to multiplicity = order, then drops the knots and
// controls outside the domain, so the result is clamped and every non-empty span is one Bézier piece whose
// `order` controls are not shared with its neighbours. The function is unchanged on the domain.
template <class T>
AxisRefinement<T> bezier_refine_axis(const KnotVector& kv, const std::vector<T>& cps, std::size_t inner,
                                     std::size_t outer, const char* who) {
  std::vector<double> values;
  for (double u : kv.knots())
    if (u >= kv.domain_min() && u <= kv.domain_max() && (values.empty() || values.back() != u)) values.push_back(u);
  AxisRefinement<T> cur{kv, cps};
  for (double u : values) cur = insert_knot_axis(cur.knots, cur.cps, inner, outer, u, kv.order(), who);
  const std::vector<double>& U = cur.knots.knots();
  const int order = kv.order();
  const int f = static_cast<int>(std::find(U.begin(), U.end(), kv.domain_min()) - U.begin());
  const int g = static_cast<int>(U.rend() - std::find(U.rbegin(), U.rend(), kv.domain_max())) - 1;
  const int n_old = cur.knots.control_count();
  const int n_new = (g - f + 1) - order;
  if (f == 0 && n_new == n_old) return cur;
  std::vector<T> Q(inner * outer * static_cast<std::size_t>(n_new));
  for (std::size_t b = 0; b < outer; ++b)
    for (int i = 0; i < n_new; ++i)
      for (std::size_t a = 0; a < inner; ++a)
        Q[a + inner * (static_cast<std::size_t>(i) + n_new * b)] =
            cur.cps[a + inner * (static_cast<std::size_t>(i + f) + n_old * b)];
  return {KnotVector(order, std::vector<double>(U.begin() + f, U.begin() + g + 1)), std::move(Q)};
}

}  // namespace trispline::core::detail
