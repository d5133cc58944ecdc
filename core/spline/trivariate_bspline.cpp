// TrivariateBSpline<T>: evaluation with first and second partials (Piegl & Tiller A3.5/A3.6 in three variables),
// Jacobian, Boehm insertion per axis (A5.3) and Bézier extraction.
#include "core/spline/trivariate_bspline.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/spline/bspline_basis.h"
#include "core/spline/control_net.h"
#include "core/spline/knot_insertion.h"
#include "core/spline/scratch.h"

namespace trispline::core {
namespace {

// out[a + 3b + 9c] = ∂^{a+b+c} F / ∂u^a ∂v^b ∂w^c for a + b + c ≤ nd (nd ≤ 2). Sums are staged (i, then j, then
// k) in a fixed order, so results are bit-reproducible.
template <class T>
void eval_partials(const TrivariateBSpline<T>& F, const glm::dvec3& uvw_in, int nd, T* out) {
  for (int a = 0; a < 3; ++a) detail::check_parameter(uvw_in[a], "TrivariateBSpline::eval");
  const KnotVector& ku = F.knots(0);
  const KnotVector& kv = F.knots(1);
  const KnotVector& kw = F.knots(2);
  const int ou = ku.order(), ov = kv.order(), ow = kw.order();
  const int su = ku.find_span(uvw_in.x), sv = kv.find_span(uvw_in.y), sw = kw.find_span(uvw_in.z);
  const double u = ku.wrap_or_clamp(uvw_in.x), v = kv.wrap_or_clamp(uvw_in.y), w = kw.wrap_or_clamp(uvw_in.z);
  detail::Scratch<24> Nu(static_cast<std::size_t>((nd + 1) * ou)), Nv(static_cast<std::size_t>((nd + 1) * ov)),
      Nw(static_cast<std::size_t>((nd + 1) * ow));
  basis_derivatives(ku, su, u, nd, Nu.data());
  basis_derivatives(kv, sv, v, nd, Nv.data());
  basis_derivatives(kw, sw, w, nd, Nw.data());
  // Control indices per axis (wrapped mod period on periodic axes).
  const glm::ivec3 cnt = F.control_counts();
  auto axis_index = [](const KnotVector& kn, int first, int r, int count) {
    const int i = first + r;
    return kn.is_periodic() ? i % count : i;
  };
  const int fu = su - ou + 1, fv = sv - ov + 1, fw = sw - ow + 1;
  const std::vector<T>& P = F.control_points();
  for (int i = 0; i < 27; ++i) out[i] = T(0.0);
  for (int k = 0; k < ow; ++k) {
    T B[9];
    for (int i = 0; i < 9; ++i) B[i] = T(0.0);
    const int ck = axis_index(kw, fw, k, cnt.z);
    for (int j = 0; j < ov; ++j) {
      T A[3] = {T(0.0), T(0.0), T(0.0)};
      const int cj = axis_index(kv, fv, j, cnt.y);
      for (int i = 0; i < ou; ++i) {
        const T& q = P[F.index(axis_index(ku, fu, i, cnt.x), cj, ck)];
        for (int a = 0; a <= nd; ++a) A[a] += q * Nu[a * ou + i];
      }
      for (int a = 0; a <= nd; ++a)
        for (int b = 0; a + b <= nd; ++b) B[a + 3 * b] += A[a] * Nv[b * ov + j];
    }
    for (int a = 0; a <= nd; ++a)
      for (int b = 0; a + b <= nd; ++b)
        for (int c = 0; a + b + c <= nd; ++c) out[a + 3 * b + 9 * c] += B[a + 3 * b] * Nw[c * ow + k];
  }
}

void reject_periodic(const KnotVector& kv, int axis, const char* who) {
  if (kv.is_periodic())
    throw std::invalid_argument(std::string(who) + ": axis " + std::to_string(axis) +
                                " has a periodic knot vector; knot refinement of periodic lattices is not supported");
}

constexpr int kUnit[3] = {1, 3, 9};  // stride of one derivative order along u, v, w in eval_partials' output

}  // namespace

template <class T>
TrivariateBSpline<T>::TrivariateBSpline(KnotVector ku, KnotVector kv, KnotVector kw, std::vector<T> control_points)
    : k_{std::move(ku), std::move(kv), std::move(kw)}, cps_(std::move(control_points)) {
  const glm::ivec3 c = control_counts();
  detail::check_control_points(cps_, static_cast<std::size_t>(c.x) * c.y * c.z, "TrivariateBSpline");
}

template <class T>
glm::ivec3 TrivariateBSpline<T>::control_counts() const {
  return {k_[0].stored_control_count(), k_[1].stored_control_count(), k_[2].stored_control_count()};
}

template <class T>
glm::ivec3 TrivariateBSpline<T>::orders() const {
  return {k_[0].order(), k_[1].order(), k_[2].order()};
}

template <class T>
std::size_t TrivariateBSpline<T>::index(int i, int j, int k) const {
  const std::size_t l = static_cast<std::size_t>(k_[0].stored_control_count());
  const std::size_t m = static_cast<std::size_t>(k_[1].stored_control_count());
  return static_cast<std::size_t>(i) + l * (static_cast<std::size_t>(j) + m * static_cast<std::size_t>(k));
}

template <class T>
T TrivariateBSpline<T>::eval(const glm::dvec3& uvw) const {
  T d[27];
  eval_partials(*this, uvw, 0, d);
  return d[0];
}

template <class T>
typename TrivariateBSpline<T>::FirstDerivatives TrivariateBSpline<T>::eval_first(const glm::dvec3& uvw) const {
  T d[27];
  eval_partials(*this, uvw, 1, d);
  return {d[0], {d[kUnit[0]], d[kUnit[1]], d[kUnit[2]]}};
}

template <class T>
typename TrivariateBSpline<T>::SecondDerivatives TrivariateBSpline<T>::eval_second(const glm::dvec3& uvw) const {
  T d[27];
  eval_partials(*this, uvw, 2, d);
  SecondDerivatives s{d[0], {d[kUnit[0]], d[kUnit[1]], d[kUnit[2]]}, {}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) s.dd[a][b] = d[kUnit[a] + kUnit[b]];
  return s;
}

template <class T>
void TrivariateBSpline<T>::insert_knot(int axis, double t, int times) {
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("TrivariateBSpline::insert_knot: axis must be 0 (u), 1 (v) or 2 (w), got " +
                                std::to_string(axis));
  reject_periodic(k_[axis], axis, "TrivariateBSpline::insert_knot");
  const glm::ivec3 c = control_counts();
  const std::size_t inner = axis == 0 ? 1 : axis == 1 ? c.x : static_cast<std::size_t>(c.x) * c.y;
  const std::size_t outer = axis == 2 ? 1 : axis == 1 ? c.z : static_cast<std::size_t>(c.y) * c.z;
  auto r = detail::insert_knot_axis(k_[axis], cps_, inner, outer, t, times, "TrivariateBSpline::insert_knot");
  k_[axis] = std::move(r.knots);
  cps_ = std::move(r.cps);
}

template <class T>
TrivariateBSpline<T> TrivariateBSpline<T>::periodic_unwrapped() const {
  if (!k_[0].is_periodic() && !k_[1].is_periodic() && !k_[2].is_periodic()) return *this;
  std::array<KnotVector, 3> k = k_;
  const glm::ivec3 stored = control_counts();
  glm::ivec3 full;
  for (int a = 0; a < 3; ++a) {
    full[a] = k[a].control_count();
    if (k[a].is_periodic()) k[a] = KnotVector(k[a].order(), k[a].knots());
  }
  std::vector<T> P(static_cast<std::size_t>(full.x) * full.y * full.z);
  for (int w = 0; w < full.z; ++w)
    for (int v = 0; v < full.y; ++v)
      for (int u = 0; u < full.x; ++u)
        P[u + static_cast<std::size_t>(full.x) * (v + static_cast<std::size_t>(full.y) * w)] =
            control_point(u % stored.x, v % stored.y, w % stored.z);
  return TrivariateBSpline<T>(std::move(k[0]), std::move(k[1]), std::move(k[2]), std::move(P));
}

template <class T>
TrivariateBSpline<T> TrivariateBSpline<T>::bezier_extracted() const {
  for (int axis = 0; axis < 3; ++axis) reject_periodic(k_[axis], axis, "TrivariateBSpline::bezier_extracted");
  std::array<KnotVector, 3> k = k_;
  std::vector<T> P = cps_;
  for (int axis = 0; axis < 3; ++axis) {
    const glm::ivec3 c(k[0].control_count(), k[1].control_count(), k[2].control_count());
    const std::size_t inner = axis == 0 ? 1 : axis == 1 ? c.x : static_cast<std::size_t>(c.x) * c.y;
    const std::size_t outer = axis == 2 ? 1 : axis == 1 ? c.z : static_cast<std::size_t>(c.y) * c.z;
    auto r = detail::bezier_refine_axis(k[axis], P, inner, outer, "TrivariateBSpline::bezier_extracted");
    k[axis] = std::move(r.knots);
    P = std::move(r.cps);
  }
  return TrivariateBSpline<T>(std::move(k[0]), std::move(k[1]), std::move(k[2]), std::move(P));
}

glm::dmat3 jacobian(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& uvw) {
  const auto f = F.eval_first(uvw);
  return glm::dmat3(f.d[0], f.d[1], f.d[2]);
}

double jacobian_determinant(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& uvw) {
  return glm::determinant(jacobian(F, uvw));
}

template class TrivariateBSpline<double>;
template class TrivariateBSpline<glm::dvec3>;

}  // namespace trispline::core
