// KnotVector: validation, factories, span search and Greville abscissae (Piegl & Tiller ch. 2, A2.1).
#include "core/spline/knot_vector.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace trispline::core {
namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("KnotVector: " + what); }

std::string str(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

void check_counts(int order, int control_count) {
  if (order < 1) fail("order must be >= 1 (order = degree + 1), got " + std::to_string(order));
  if (control_count < order)
    fail("order " + std::to_string(order) + " exceeds control count " + std::to_string(control_count) +
         " (a B-spline of order k needs at least k control points)");
}

}  // namespace

KnotVector::KnotVector(int order, std::vector<double> knots) : order_(order), knots_(std::move(knots)) {
  if (order_ < 1) fail("order must be >= 1 (order = degree + 1), got " + std::to_string(order_));
  const int n = static_cast<int>(knots_.size()) - order_;
  if (n < order_)
    fail("order " + std::to_string(order_) + " exceeds control count " + std::to_string(n) + " (" +
         std::to_string(knots_.size()) + " knots = control count + order; need at least " + std::to_string(2 * order_) +
         ")");
  for (std::size_t i = 0; i < knots_.size(); ++i)
    if (!std::isfinite(knots_[i])) fail("knot " + std::to_string(i) + " is not finite (" + str(knots_[i]) + ")");
  for (std::size_t i = 1; i < knots_.size(); ++i)
    if (knots_[i] < knots_[i - 1])
      fail("knots must be non-decreasing, but knots[" + std::to_string(i - 1) + "] = " + str(knots_[i - 1]) +
           " > knots[" + std::to_string(i) + "] = " + str(knots_[i]));
  int run = 1;
  for (std::size_t i = 1; i < knots_.size(); ++i) {
    run = knots_[i] == knots_[i - 1] ? run + 1 : 1;
    if (run > order_)
      fail("knot " + str(knots_[i]) + " has multiplicity > order " + std::to_string(order_) +
           " (a basis function would vanish identically)");
  }
  if (!(domain_min() < domain_max()))
    fail("empty domain: knots[order-1] = " + str(domain_min()) + " equals knots[n] = " + str(domain_max()));
}

KnotVector KnotVector::clamped_uniform(int order, int control_count) {
  check_counts(order, control_count);
  const int spans = control_count - order + 1;
  std::vector<double> k(static_cast<std::size_t>(control_count + order));
  for (int i = 0; i < order; ++i) {
    k[i] = 0.0;
    k[control_count + i] = 1.0;
  }
  for (int j = 1; j < spans; ++j) k[order - 1 + j] = static_cast<double>(j) / static_cast<double>(spans);
  return KnotVector(order, std::move(k));
}

KnotVector KnotVector::uniform(int order, int control_count) {
  check_counts(order, control_count);
  const int spans = control_count - order + 1;
  std::vector<double> k(static_cast<std::size_t>(control_count + order));
  for (int i = 0; i < control_count + order; ++i)
    k[i] = static_cast<double>(i - (order - 1)) / static_cast<double>(spans);
  return KnotVector(order, std::move(k));
}

KnotVector KnotVector::periodic_uniform(int order, int period) {
  if (order < 1) fail("order must be >= 1 (order = degree + 1), got " + std::to_string(order));
  if (period < 1) fail("periodic_uniform: period must be >= 1, got " + std::to_string(period));
  const int p = order - 1;
  std::vector<double> k(static_cast<std::size_t>(period + 2 * p + 1));
  for (int i = 0; i <= period + 2 * p; ++i) k[i] = static_cast<double>(i - p) / static_cast<double>(period);
  KnotVector kv(order, std::move(k));
  kv.period_ = period;
  return kv;
}

double KnotVector::wrap_or_clamp(double t) const {
  if (period_ > 0) {
    // Domain [0,1): t − ⌊t⌋ rounds to 1 for tiny negative t (−6.9e−18 − ⌊…⌋ = 1.0); map that to 0 so wrapping is
    // idempotent (find_span wraps again, and 1 would wrap to 0 there while the basis was evaluated at 1).
    const double w = t - std::floor(t);
    return w < 1.0 ? w : 0.0;
  }
  return t < domain_min() ? domain_min() : (t > domain_max() ? domain_max() : t);
}

KnotVector KnotVector::clamped_for_fit(int order, int control_count, const std::vector<double>& params) {
  check_counts(order, control_count);
  const int P = static_cast<int>(params.size());
  if (P < control_count)
    fail("clamped_for_fit: " + std::to_string(P) + " parameters for " + std::to_string(control_count) +
         " control points (need at least as many points as controls)");
  for (int i = 0; i < P; ++i) {
    if (!std::isfinite(params[i])) fail("clamped_for_fit: parameter " + std::to_string(i) + " is not finite");
    if (i > 0 && params[i] < params[i - 1]) fail("clamped_for_fit: parameters must be non-decreasing");
  }
  const int p = order - 1;
  std::vector<double> k(static_cast<std::size_t>(control_count + order));
  for (int i = 0; i < order; ++i) {
    k[i] = 0.0;
    k[control_count + i] = 1.0;
  }
  const int interior = control_count - order;
  if (P == control_count && p > 0) {
    // Interpolation: knot averaging (Piegl & Tiller Eq. 9.8).
    for (int j = 1; j <= interior; ++j) {
      double s = 0.0;
      for (int i = j; i < j + p; ++i) s += params[i];
      k[p + j] = s / static_cast<double>(p);
    }
  } else if (P == control_count) {
    // Order 1 interpolation: one parameter per span, breaks half-way between neighbours.
    for (int j = 1; j <= interior; ++j) k[j] = 0.5 * (params[j - 1] + params[j]);
  } else {
    // Approximation: every knot span receives at least one parameter (Piegl & Tiller Eq. 9.68–9.69).
    const double d = static_cast<double>(P) / static_cast<double>(interior + 1);
    for (int j = 1; j <= interior; ++j) {
      const int i = static_cast<int>(j * d);
      const double a = j * d - i;
      k[p + j] = (1.0 - a) * params[i - 1] + a * params[i];
    }
  }
  return KnotVector(order, std::move(k));
}

int KnotVector::find_span(double t) const {
  if (std::isnan(t)) throw std::invalid_argument("KnotVector::find_span: parameter is NaN");
  const int n = control_count();
  if (period_ > 0) t = wrap_or_clamp(t);
  if (t >= knots_[n]) {
    int s = n - 1;
    while (knots_[s] == knots_[s + 1]) --s;  // last non-empty span; terminates because the domain is non-empty
    return s;
  }
  if (t <= knots_[order_ - 1]) t = knots_[order_ - 1];
  // First knot in [order-1, n] greater than t; the span starts one before it.
  const auto first = knots_.begin() + (order_ - 1);
  const auto last = knots_.begin() + n + 1;
  return static_cast<int>(std::upper_bound(first, last, t) - knots_.begin()) - 1;
}

int KnotVector::multiplicity(double t) const { return static_cast<int>(std::count(knots_.begin(), knots_.end(), t)); }

std::vector<double> KnotVector::greville() const {
  const int n = control_count();
  const int p = degree();
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    if (p == 0) {
      g[i] = 0.5 * (knots_[i] + knots_[i + 1]);
      continue;
    }
    double s = 0.0;
    for (int j = 1; j <= p; ++j) s += knots_[i + j];
    g[i] = s / static_cast<double>(p);
  }
  return g;
}

bool KnotVector::is_clamped() const {
  if (period_ > 0) return false;
  const int n = control_count();
  for (int i = 1; i < order_; ++i)
    if (knots_[i] != knots_[0] || knots_[n + i] != knots_[n]) return false;
  return true;
}

bool KnotVector::has_uniform_spans() const {
  const int n = control_count();
  const double tol = 1e-12 * (domain_max() - domain_min());
  double h0 = -1.0;
  for (int s = order_ - 1; s < n; ++s) {
    const double h = knots_[s + 1] - knots_[s];
    if (h == 0.0) continue;
    if (h0 < 0.0)
      h0 = h;
    else if (std::abs(h - h0) > tol)
      return false;
  }
  return true;
}

}  // namespace trispline::core
