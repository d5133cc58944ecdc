// BSplineSurface<T>: evaluation and partials (Piegl & Tiller A3.5/A3.6), Boehm insertion per axis (A5.3),
// Bézier extraction.
#include "core/spline/bspline_surface.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "core/spline/bspline_basis.h"
#include "core/spline/control_net.h"
#include "core/spline/knot_insertion.h"
#include "core/spline/scratch.h"

namespace trispline::core {
namespace {

// out[a + 3·b] = ∂^{a+b} S / ∂u^a ∂v^b for a + b ≤ nd (nd ≤ 2), computed from the local basis tables.
template <class T>
void eval_partials(const BSplineSurface<T>& S, double u, double v, int nd, T* out) {
  detail::check_parameter(u, "BSplineSurface::eval");
  detail::check_parameter(v, "BSplineSurface::eval");
  const KnotVector& ku = S.knots(0);
  const KnotVector& kv = S.knots(1);
  const int ou = ku.order(), ov = kv.order();
  const int su = ku.find_span(u), sv = kv.find_span(v);
  u = std::clamp(u, ku.domain_min(), ku.domain_max());
  v = std::clamp(v, kv.domain_min(), kv.domain_max());
  detail::Scratch<24> Nu(static_cast<std::size_t>((nd + 1) * ou)), Nv(static_cast<std::size_t>((nd + 1) * ov));
  basis_derivatives(ku, su, u, nd, Nu.data());
  basis_derivatives(kv, sv, v, nd, Nv.data());
  const int fu = su - ou + 1, fv = sv - ov + 1;
  for (int i = 0; i < 9; ++i) out[i] = T(0.0);
  for (int j = 0; j < ov; ++j) {
    T row[3] = {T(0.0), T(0.0), T(0.0)};  // Σ_i ∂^a B_i(u) P_ij, a = 0..nd
    for (int i = 0; i < ou; ++i) {
      const T& P = S.control_point(fu + i, fv + j);
      for (int a = 0; a <= nd; ++a) row[a] += P * Nu[a * ou + i];
    }
    for (int a = 0; a <= nd; ++a)
      for (int b = 0; a + b <= nd; ++b) out[a + 3 * b] += row[a] * Nv[b * ov + j];
  }
}

}  // namespace

template <class T>
BSplineSurface<T>::BSplineSurface(KnotVector knots_u, KnotVector knots_v, std::vector<T> control_points)
    : ku_(std::move(knots_u)), kv_(std::move(knots_v)), cps_(std::move(control_points)) {
  detail::check_control_points(
      cps_, static_cast<std::size_t>(ku_.control_count()) * static_cast<std::size_t>(kv_.control_count()),
      "BSplineSurface");
}

template <class T>
T BSplineSurface<T>::eval(double u, double v) const {
  T d[9];
  eval_partials(*this, u, v, 0, d);
  return d[0];
}

template <class T>
typename BSplineSurface<T>::FirstDerivatives BSplineSurface<T>::eval_first(double u, double v) const {
  T d[9];
  eval_partials(*this, u, v, 1, d);
  return {d[0], d[1], d[3]};
}

template <class T>
typename BSplineSurface<T>::SecondDerivatives BSplineSurface<T>::eval_second(double u, double v) const {
  T d[9];
  eval_partials(*this, u, v, 2, d);
  return {d[0], d[1], d[3], d[2], d[4], d[6]};
}

template <class T>
glm::dvec3 BSplineSurface<T>::normal(double u, double v) const {
  if constexpr (std::is_same_v<T, glm::dvec3>) {
    const FirstDerivatives f = eval_first(u, v);
    const glm::dvec3 n = glm::cross(f.du, f.dv);
    const double len = glm::length(n);
    return len > 0.0 ? n / len : glm::dvec3(0.0);
  } else {
    throw std::logic_error("BSplineSurface::normal needs T = glm::dvec3");
  }
}

template <class T>
void BSplineSurface<T>::insert_knot(int axis, double t, int times) {
  if (axis != 0 && axis != 1)
    throw std::invalid_argument("BSplineSurface::insert_knot: axis must be 0 (u) or 1 (v), got " +
                                std::to_string(axis));
  const std::size_t nu = static_cast<std::size_t>(ku_.control_count());
  const std::size_t nv = static_cast<std::size_t>(kv_.control_count());
  if (axis == 0) {
    auto r = detail::insert_knot_axis(ku_, cps_, 1, nv, t, times, "BSplineSurface::insert_knot");
    ku_ = std::move(r.knots);
    cps_ = std::move(r.cps);
  } else {
    auto r = detail::insert_knot_axis(kv_, cps_, nu, 1, t, times, "BSplineSurface::insert_knot");
    kv_ = std::move(r.knots);
    cps_ = std::move(r.cps);
  }
}

template <class T>
BSplineSurface<T> BSplineSurface<T>::bezier_extracted() const {
  const std::size_t nv = static_cast<std::size_t>(kv_.control_count());
  auto ru = detail::bezier_refine_axis(ku_, cps_, 1, nv, "BSplineSurface::bezier_extracted");
  const std::size_t nu = static_cast<std::size_t>(ru.knots.control_count());
  auto rv = detail::bezier_refine_axis(kv_, ru.cps, nu, 1, "BSplineSurface::bezier_extracted");
  return BSplineSurface<T>(std::move(ru.knots), std::move(rv.knots), std::move(rv.cps));
}

template class BSplineSurface<double>;
template class BSplineSurface<glm::dvec2>;
template class BSplineSurface<glm::dvec3>;

}  // namespace trispline::core
