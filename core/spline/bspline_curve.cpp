// BSplineCurve<T>: evaluation (Piegl & Tiller A3.1), derivatives (A3.2), Boehm insertion (A5.1), Bézier pieces.
#include "core/spline/bspline_curve.h"

#include <algorithm>
#include <stdexcept>

#include "core/spline/bspline_basis.h"
#include "core/spline/control_net.h"
#include "core/spline/knot_insertion.h"
#include "core/spline/scratch.h"

namespace trispline::core {

template <class T>
BSplineCurve<T>::BSplineCurve(KnotVector knots, std::vector<T> control_points)
    : knots_(std::move(knots)), cps_(std::move(control_points)) {
  detail::check_control_points(cps_, static_cast<std::size_t>(knots_.control_count()), "BSplineCurve");
}

template <class T>
T BSplineCurve<T>::eval(double t) const {
  detail::check_parameter(t, "BSplineCurve::eval");
  const int order = knots_.order();
  const int span = knots_.find_span(t);
  t = std::min(std::max(t, knots_.domain_min()), knots_.domain_max());
  detail::Scratch<16> N(static_cast<std::size_t>(order));
  basis_functions(knots_, span, t, N.data());
  const int first = span - order + 1;
  T c = cps_[first] * N[0];
  for (int r = 1; r < order; ++r) c += cps_[first + r] * N[r];
  return c;
}

template <class T>
std::vector<T> BSplineCurve<T>::derivatives(double t, int n_deriv) const {
  detail::check_parameter(t, "BSplineCurve::derivatives");
  if (n_deriv < 0) throw std::invalid_argument("BSplineCurve::derivatives: n_deriv must be >= 0");
  const int order = knots_.order();
  const int span = knots_.find_span(t);
  t = std::min(std::max(t, knots_.domain_min()), knots_.domain_max());
  detail::Scratch<48> D(static_cast<std::size_t>((n_deriv + 1) * order));
  basis_derivatives(knots_, span, t, n_deriv, D.data());
  const int first = span - order + 1;
  std::vector<T> out(static_cast<std::size_t>(n_deriv + 1));
  for (int d = 0; d <= n_deriv; ++d) {
    T c = cps_[first] * D[d * order];
    for (int r = 1; r < order; ++r) c += cps_[first + r] * D[d * order + r];
    out[d] = c;
  }
  return out;
}

template <class T>
void BSplineCurve<T>::insert_knot(double t, int times) {
  auto r = detail::insert_knot_axis(knots_, cps_, 1, 1, t, times, "BSplineCurve::insert_knot");
  knots_ = std::move(r.knots);
  cps_ = std::move(r.cps);
}

template <class T>
BSplineCurve<T> BSplineCurve<T>::bezier_extracted() const {
  auto r = detail::bezier_refine_axis(knots_, cps_, 1, 1, "BSplineCurve::bezier_extracted");
  return BSplineCurve<T>(std::move(r.knots), std::move(r.cps));
}

template <class T>
std::vector<BSplineCurve<T>> BSplineCurve<T>::bezier_pieces() const {
  const BSplineCurve<T> all = bezier_extracted();
  const int order = all.order();
  const std::vector<double>& U = all.knots().knots();
  std::vector<BSplineCurve<T>> pieces;
  for (int s = order - 1; s < all.knots().control_count(); ++s) {
    if (U[s] == U[s + 1]) continue;
    std::vector<double> k(static_cast<std::size_t>(2 * order));
    for (int i = 0; i < order; ++i) {
      k[i] = U[s];
      k[order + i] = U[s + 1];
    }
    std::vector<T> P(all.control_points().begin() + (s - order + 1), all.control_points().begin() + (s + 1));
    pieces.emplace_back(KnotVector(order, std::move(k)), std::move(P));
  }
  return pieces;
}

template class BSplineCurve<double>;
template class BSplineCurve<glm::dvec2>;
template class BSplineCurve<glm::dvec3>;

}  // namespace trispline::core
