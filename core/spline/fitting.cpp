// Least-squares fitting with interpolated end points (Piegl & Tiller ch. 9.4.1), parametrisations (ch. 9.2.1).
#include "core/spline/fitting.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/spline/band_cholesky.h"
#include "core/spline/bspline_basis.h"
#include "core/spline/control_net.h"

namespace trispline::core {
namespace {

double distance(double a, double b) { return std::abs(a - b); }
template <int L>
double distance(const glm::vec<L, double>& a, const glm::vec<L, double>& b) {
  return glm::length(a - b);
}

[[noreturn]] void fail(const char* who, const std::string& what) {
  throw std::invalid_argument(std::string(who) + ": " + what);
}

// Normal equations of the endpoint-constrained LSQ problem for fixed knots and parameters, factorised once and
// reused for every row / column of a surface fit.
class CurveFitter {
 public:
  CurveFitter(const KnotVector& kv, const std::vector<double>& params, const char* who)
      : kv_(kv), who_(who), params_(params) {
    const int n = kv.control_count(), order = kv.order(), P = static_cast<int>(params.size());
    if (!kv.is_clamped()) fail(who, "the knot vector must be clamped (end knots of multiplicity = order)");
    if (n < 2) fail(who, "need at least 2 control points to interpolate both end points, got " + std::to_string(n));
    if (P < n)
      fail(who, "degenerate input: " + std::to_string(P) + " points for " + std::to_string(n) +
                    " control points (need at least as many points as control points)");
    const double len = kv.domain_max() - kv.domain_min();
    for (int k = 0; k < P; ++k) {
      if (!std::isfinite(params_[k])) fail(who, "parameter " + std::to_string(k) + " is not finite");
      if (k > 0 && params_[k] < params_[k - 1]) fail(who, "parameters must be non-decreasing");
    }
    if (std::abs(params_.front() - kv.domain_min()) > 1e-12 * len ||
        std::abs(params_.back() - kv.domain_max()) > 1e-12 * len)
      fail(who, "parameters must run from the domain start " + std::to_string(kv.domain_min()) + " to its end " +
                    std::to_string(kv.domain_max()) + " (end points are interpolated)");
    params_.front() = kv.domain_min();
    params_.back() = kv.domain_max();
    // Basis values at every interior parameter; normal matrix over the interior controls 1..n-2.
    span_.resize(P);
    N_.resize(static_cast<std::size_t>(P) * order);
    for (int k = 0; k < P; ++k) {
      span_[k] = kv.find_span(params_[k]);
      basis_functions(kv, span_[k], params_[k], &N_[static_cast<std::size_t>(k) * order]);
    }
    const int m = n - 2, b = order - 1;
    if (m == 0) return;
    std::vector<double> band(static_cast<std::size_t>(m) * (b + 1), 0.0);
    for (int k = 1; k < P - 1; ++k) {
      const int first = span_[k] - order + 1;
      for (int r = 0; r < order; ++r) {
        const int gi = first + r;
        if (gi < 1 || gi > n - 2) continue;
        for (int s = 0; s <= r; ++s) {
          const int gj = first + s;
          if (gj < 1) continue;
          band[static_cast<std::size_t>(gi - 1) * (b + 1) + (r - s)] += basis(k, r) * basis(k, s);
        }
      }
    }
    try {
      solver_.emplace(m, b, std::move(band));
    } catch (const std::invalid_argument&) {
      fail(who,
           "the normal equations are singular: some control point's basis function has no parameter in its "
           "support (too few or too clustered parameters for " +
               std::to_string(n) + " control points)");
    }
  }

  // Control points (#n) fitted to points[k·stride], k ∈ [0, #P).
  template <class T>
  std::vector<T> fit(const T* points, std::size_t stride) const {
    const int n = kv_.control_count(), order = kv_.order(), P = static_cast<int>(params_.size());
    for (int k = 0; k < P; ++k)
      if (!detail::is_finite(points[k * stride])) fail(who_, "point " + std::to_string(k) + " is not finite");
    const T& Q0 = points[0];
    const T& Qm = points[static_cast<std::size_t>(P - 1) * stride];
    std::vector<T> cps(static_cast<std::size_t>(std::max(n, 2)), T(0.0));  // n >= 2 (checked in the constructor)
    cps[0] = Q0;
    cps[cps.size() - 1] = Qm;
    if (n == 2) return cps;
    // rhs_i = Σ_k N_i(ū_k) R_k with R_k = Q_k − N_0(ū_k) Q_0 − N_{n−1}(ū_k) Q_m (P&T Eq. 9.63–9.67).
    T* rhs = cps.data() + 1;
    for (int k = 1; k < P - 1; ++k) {
      const int first = span_[k] - order + 1;
      T R = points[k * stride];
      for (int r = 0; r < order; ++r) {
        if (first + r == 0) R -= Q0 * basis(k, r);
        if (first + r == n - 1) R -= Qm * basis(k, r);
      }
      for (int r = 0; r < order; ++r) {
        const int gi = first + r;
        if (gi >= 1 && gi <= n - 2) rhs[gi - 1] += R * basis(k, r);
      }
    }
    solver_->solve(rhs);
    return cps;
  }

  const KnotVector& knots() const { return kv_; }

 private:
  double basis(int k, int r) const { return N_[static_cast<std::size_t>(k) * kv_.order() + r]; }
  KnotVector kv_;
  const char* who_;
  std::vector<double> params_;
  std::vector<int> span_;
  std::vector<double> N_;
  std::optional<BandCholesky> solver_;
};

}  // namespace

template <class T>
std::vector<double> parametrize(const std::vector<T>& points, Parametrization kind) {
  const std::size_t P = points.size();
  if (P < 2) throw std::invalid_argument("parametrize: need at least 2 points, got " + std::to_string(P));
  for (std::size_t i = 0; i < P; ++i)
    if (!detail::is_finite(points[i]))
      throw std::invalid_argument("parametrize: point " + std::to_string(i) + " is not finite");
  std::vector<double> t(P, 0.0);
  if (kind != Parametrization::Uniform) {
    for (std::size_t i = 1; i < P; ++i) {
      const double d = distance(points[i], points[i - 1]);
      t[i] = t[i - 1] + (kind == Parametrization::Centripetal ? std::sqrt(d) : d);
    }
    const double total = t.back();
    if (total > 0.0) {
      for (std::size_t i = 1; i + 1 < P; ++i) t[i] /= total;
      t.back() = 1.0;
      return t;
    }
  }
  for (std::size_t i = 1; i + 1 < P; ++i) t[i] = static_cast<double>(i) / static_cast<double>(P - 1);
  t.back() = 1.0;
  return t;
}

template <class T>
BSplineCurve<T> fit_curve(const std::vector<T>& points, const std::vector<double>& params, const KnotVector& knots) {
  if (points.size() != params.size())
    fail("fit_curve", std::to_string(points.size()) + " points but " + std::to_string(params.size()) + " parameters");
  CurveFitter f(knots, params, "fit_curve");
  return BSplineCurve<T>(knots, f.fit(points.data(), 1));
}

template <class T>
BSplineCurve<T> fit_curve(const std::vector<T>& points, const std::vector<double>& params, int order,
                          int control_count) {
  if (points.size() != params.size())
    fail("fit_curve", std::to_string(points.size()) + " points but " + std::to_string(params.size()) + " parameters");
  if (static_cast<int>(points.size()) < control_count)
    fail("fit_curve", "degenerate input: " + std::to_string(points.size()) + " points for " +
                          std::to_string(control_count) + " control points (need at least as many points)");
  return fit_curve(points, params, KnotVector::clamped_for_fit(order, control_count, params));
}

template <class T>
BSplineSurface<T> fit_surface(const std::vector<T>& grid, int pu, int pv, const std::vector<double>& params_u,
                              const std::vector<double>& params_v, const KnotVector& knots_u,
                              const KnotVector& knots_v) {
  if (pu < 0 || pv < 0 || grid.size() != static_cast<std::size_t>(pu) * static_cast<std::size_t>(pv))
    fail("fit_surface", "grid has " + std::to_string(grid.size()) + " points, expected pu·pv = " + std::to_string(pu) +
                            "·" + std::to_string(pv));
  if (params_u.size() != static_cast<std::size_t>(pu) || params_v.size() != static_cast<std::size_t>(pv))
    fail("fit_surface", "params_u / params_v sizes must equal pu / pv");
  const CurveFitter fu(knots_u, params_u, "fit_surface (u)");
  const CurveFitter fv(knots_v, params_v, "fit_surface (v)");
  const std::size_t cu = static_cast<std::size_t>(knots_u.control_count());
  const std::size_t cv = static_cast<std::size_t>(knots_v.control_count());
  std::vector<T> rows(cu * static_cast<std::size_t>(pv));  // rows[i + cu·j]: row j fitted in u
  for (int j = 0; j < pv; ++j) {
    const std::vector<T> c = fu.fit(grid.data() + static_cast<std::size_t>(j) * pu, 1);
    std::copy(c.begin(), c.end(), rows.begin() + cu * j);
  }
  std::vector<T> cps(cu * cv);
  for (std::size_t i = 0; i < cu; ++i) {
    const std::vector<T> c = fv.fit(rows.data() + i, cu);
    for (std::size_t j = 0; j < cv; ++j) cps[i + cu * j] = c[j];
  }
  return BSplineSurface<T>(knots_u, knots_v, std::move(cps));
}

template <class T>
BSplineSurface<T> fit_surface(const std::vector<T>& grid, int pu, int pv, const std::vector<double>& params_u,
                              const std::vector<double>& params_v, int order_u, int order_v, int control_count_u,
                              int control_count_v) {
  if (pu < control_count_u || pv < control_count_v)
    fail("fit_surface", "degenerate input: a " + std::to_string(pu) + "×" + std::to_string(pv) + " grid for " +
                            std::to_string(control_count_u) + "×" + std::to_string(control_count_v) +
                            " control points (need at least as many points as controls per axis)");
  return fit_surface(grid, pu, pv, params_u, params_v, KnotVector::clamped_for_fit(order_u, control_count_u, params_u),
                     KnotVector::clamped_for_fit(order_v, control_count_v, params_v));
}

#define TRISPLINE_FITTING_INSTANTIATE(T)                                                                       \
  template std::vector<double> parametrize<T>(const std::vector<T>&, Parametrization);                         \
  template BSplineCurve<T> fit_curve<T>(const std::vector<T>&, const std::vector<double>&, int, int);          \
  template BSplineCurve<T> fit_curve<T>(const std::vector<T>&, const std::vector<double>&, const KnotVector&); \
  template BSplineSurface<T> fit_surface<T>(const std::vector<T>&, int, int, const std::vector<double>&,       \
                                            const std::vector<double>&, int, int, int, int);                   \
  template BSplineSurface<T> fit_surface<T>(const std::vector<T>&, int, int, const std::vector<double>&,       \
                                            const std::vector<double>&, const KnotVector&, const KnotVector&);

TRISPLINE_FITTING_INSTANTIATE(double)
TRISPLINE_FITTING_INSTANTIATE(glm::dvec2)
TRISPLINE_FITTING_INSTANTIATE(glm::dvec3)

}  // namespace trispline::core
