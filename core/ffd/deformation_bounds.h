// trispline::core certified deformation-error bounds of triangles mapped through an FFD (seed ch. 3, §3.2).
//
// A triangle of an embedded mesh has its vertices at parameter points a, b, c ∈ [0,1]³; the deformed mesh draws the
// flat triangle through F(a), F(b), F(c), while the deformation maps the triangle's points to F(T(s,t)) with
// T(s,t) = c + s(a − c) + t(b − c). The deformation error is ε_{F,T} = sup ‖F(T(s,t)) − T_F(s,t)‖ (T_F the flat
// triangle, seed Def. 2), world units. Bounds from the second partial derivatives of F:
//   * per Bézier cell, M_ab ≥ sup ‖∂²F/∂a∂b‖ (a, b ∈ {u,v,w}) from the norms of the second differences of its Bézier
//     control points (convex hull property; not sampled);
//   * per triangle, the cells its parameter bounding box meets give M_ab, and with e1 = a − c, e2 = b − c
//     M1 = Σ|e1_a||e1_b|M_ab ≥ sup‖G_ss‖, M2 = Σ|e1_a||e2_b|M_ab ≥ sup‖G_st‖, M3 = Σ|e2_a||e2_b|M_ab ≥ sup‖G_tt‖
//     for G = F∘T (seed Eq. 3.4);
//   * right_triangle: in (s,t) every triangle is the right triangle with unit legs, so Filip, Magedson & Markot's
//     Theorem 4 (as the seed quotes it) gives ε ≤ (M1 + 2M2 + M3)/8; the smallest over the three choices of the
//     right-angle vertex;
//   * enclosing_circle: ε ≤ ½ R² λ, R the radius of the smallest circle enclosing the parameter triangle (the
//     circumradius for an acute triangle, half the longest edge for an obtuse one; Waldron 1998, never worse than the
//     seed's circumradius bound of §3.2.1) and λ ≥ max over unit directions v of Σ|v_a||v_b|M_ab, taken as the smaller
//     of M's largest row sum and its Frobenius norm (both bound its largest eigenvalue, which bounds that maximum);
//   * circumcircle: the seed's own general-triangle bound (§3.2.1, Lemmas 1–2, Eq. 3.5): the same ½ r² λ with r the
//     circumradius (larger than R for obtuse triangles, unbounded as a triangle degenerates; +∞ for a degenerate
//     one), kept to compare with the seed;
//   * best: the smaller of right_triangle and enclosing_circle (circumcircle is never smaller than enclosing_circle).
// The bounds need F ∈ C¹ along the triangle (Taylor with the second derivatives' sup): an order-2 (piecewise
// trilinear) axis is only C⁰ across its knot planes, so a triangle crossing one of them gets no bound (+∞; split it).
// F is clamped outside its domain (only C⁰ at the domain's faces): a triangle reaching out of it gets no bound either.
// Periodic axes (ring lattices) are unwrapped: parameters may run past the domain along them, as the FFD wraps them.
// Units: parameters in [0,1]³ (the lattice's knot domain), errors in the control points' units (world units for an
// FFD). Lattices of order ≥ 2.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

enum class ErrorBound { right_triangle, circumcircle, enclosing_circle, best };
const char* error_bound_name(ErrorBound m);  // "right_triangle", "circumcircle", "enclosing_circle", "best"

// Per-cell bounds on the second partials of F, made once per lattice.
class SecondDerivativeBounds {
 public:
  // Throws std::invalid_argument: an order below 2, non-finite control points. Periodic axes are unwrapped (their cells
  // repeat every period: parameters along them may run past the domain, as an FFD wraps them). Each Bézier cell is
  // also halved (de Casteljau, all three axes) up to 4 times, as long as the sub-boxes of all levels number at most
  // `max_sub_boxes`, and bounded per sub-box: the second derivatives of a small triangle are bounded over the part of
  // the cell it lies in, not the whole cell (the bounds follow a local bump instead of spreading it over its cell).
  explicit SecondDerivativeBounds(const TrivariateBSpline<glm::dvec3>& F, std::size_t max_sub_boxes = 8192);

  // M (symmetric 3 × 3: M[a][b] ≥ sup ‖∂²F/∂a∂b‖) over the box lo…hi (parameters, clamped to the domain): the finest
  // sub-boxes of every cell meeting it.
  glm::dmat3 over_box(const glm::dvec3& lo, const glm::dvec3& hi) const;
  // K (symmetric 3 × 3: K[a][b] ≥ sup |∂²F/∂a∂b · n|, ≤ M[a][b]) over the box, for a fixed direction n (unit), from the
  // component boxes of the second partials' Bézier control points.
  glm::dmat3 over_box_along(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& n) const;
  // Whether the open box lo…hi crosses a knot plane of an order-2 axis (where F is only C⁰).
  bool crosses_kink(const glm::dvec3& lo, const glm::dvec3& hi) const;
  // Whether the box lies in F's domain on its non-periodic axes (up to 1e-9 of the domain): outside, F is clamped —
  // continuous but not C¹ at the domain's faces, so a triangle reaching out gets no bound.
  bool in_domain(const glm::dvec3& lo, const glm::dvec3& hi) const;
  std::size_t cell_count() const { return static_cast<std::size_t>(cells_.x) * cells_.y * cells_.z; }
  int sub_levels() const { return static_cast<int>(levels_.size()) - 1; }  // halvings per cell kept (0…4)

  // Per (sub-)box: for each second partial (uu, vv, ww, uv, uw, vw) the largest norm of its Bézier control points
  // (m) and their component box (centre xyz, half-width xyz).
  struct BoxBound {
    std::array<double, 6> m{};
    std::array<double, 36> box{};
  };

 private:
  std::array<std::vector<double>, 3> breaks_;  // distinct knots per axis: cell i of an axis is [breaks[i], breaks[i+1]]
  std::array<std::vector<double>, 3> inv_size_;  // 1 / (breaks[i+1] − breaks[i])
  glm::ivec3 cells_{0};
  glm::bvec3 c0_{false};  // order-2 axes
  // The cell of x along axis a (upper: a point on a knot plane counts for the cell above); on a periodic axis an
  // unrolled index (cell + period · cells).
  int cell_index(int a, double x, bool upper) const;
  // Calls fn(level, index into levels_[level]) for the finest sub-boxes of every cell meeting the box lo…hi.
  template <class PerBox>
  void for_boxes(const glm::dvec3& lo, const glm::dvec3& hi, PerBox&& fn) const;
  glm::bvec3 periodic_{false};
  glm::dvec3 domain_lo_{0.0}, domain_hi_{1.0};
  // levels_[l][cell · 8^l + sx + 2^l (sy + 2^l sz)]: the bounds of sub-box (sx, sy, sz) of a cell halved l times; the
  // norms (what over_box reads, for every triangle) apart from the component boxes (over_box_along only).
  std::vector<std::vector<std::array<double, 6>>> levels_;
  std::vector<std::vector<std::array<double, 36>>> level_boxes_;
};

// The bound on ε_{F,T} of the parameter triangle (a, b, c), world units; +∞ when it crosses a C⁰ knot plane.
double triangle_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c, ErrorBound method = ErrorBound::best);

// triangle_error_bound of every triangle (#F, indices into params #V × 3, evaluated at params + param_offset),
// in parallel. Throws std::invalid_argument on an index out of range.
std::vector<double> triangle_error_bounds(const SecondDerivativeBounds& bounds, const std::vector<glm::dvec3>& params,
                                          const std::vector<glm::uvec3>& triangles,
                                          const glm::dvec3& param_offset = glm::dvec3(0.0),
                                          ErrorBound method = ErrorBound::best);

// The normal-projected bound (seed §3.2.2, Eq. 3.7): sup |(F(T(s,t)) − T_F(s,t)) · n| for a fixed unit direction n —
// pass the unit normal of the drawn (deformed flat) triangle — world units; +∞ across a C⁰ knot plane. The same
// theorems applied to the scalar (F∘T − T_F)·n, whose second partials are Σ e_a e_b (∂²F/∂a∂b · n): motion of the
// surface within the triangle's plane (a tangential reparametrization, seed's x = s² example) costs nothing. The
// seed projects onto the surface's varying normal n(u,v); that variant is not a bound as stated (the derivatives of
// n(u,v) enter the Taylor remainder), so the fixed normal of the drawn triangle is used: the distance of the true
// surface from the plane the renderer draws, which is what shading and silhouettes show. Always ≤ the full bound's
// counterpart of the same method.
double triangle_normal_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c, const glm::dvec3& n, ErrorBound method = ErrorBound::best);

// ε_{F,T} measured: ‖F(T(s,t)) − T_F(s,t)‖ on the barycentric grid of `n` steps per edge (n ≥ 1), the worst sample
// refined on two finer grids around it, then by Newton's method on ½‖E‖² (with F's exact second derivatives) from
// there. For checking the bounds and their tightness: a lower bound of ε, not a bound on it. Throws
// std::invalid_argument for n < 1.
double triangle_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, int n = 24);
// The same for the projected error |(F∘T − T_F) · normal| (a lower bound of it, for checking the normal bound).
double triangle_normal_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c, const glm::dvec3& normal, int n = 24);

}  // namespace trispline::core
