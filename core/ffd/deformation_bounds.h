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
//   * best: the smaller of the two.
// The bounds need F ∈ C¹ along the triangle (Taylor with the second derivatives' sup): an order-2 (piecewise
// trilinear) axis is only C⁰ across its knot planes, so a triangle crossing one of them gets no bound (+∞; split it).
// Units: parameters in [0,1]³ (the lattice's knot domain), errors in the control points' units (world units for an
// FFD). Non-periodic lattices of order ≥ 2.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

enum class ErrorBound { right_triangle, enclosing_circle, best };

// Per-cell bounds on the second partials of F, made once per lattice.
class SecondDerivativeBounds {
 public:
  // Throws std::invalid_argument: a periodic axis, an order below 2, non-finite control points.
  explicit SecondDerivativeBounds(const TrivariateBSpline<glm::dvec3>& F);

  // M (symmetric 3 × 3: M[a][b] ≥ sup ‖∂²F/∂a∂b‖) over the cells meeting the box lo…hi (parameters, clamped to the
  // domain).
  glm::dmat3 over_box(const glm::dvec3& lo, const glm::dvec3& hi) const;
  // Whether the open box lo…hi crosses a knot plane of an order-2 axis (where F is only C⁰).
  bool crosses_kink(const glm::dvec3& lo, const glm::dvec3& hi) const;
  std::size_t cell_count() const { return m_.size(); }

 private:
  std::array<std::vector<double>, 3> breaks_;  // distinct knots per axis: cell i of an axis is [breaks[i], breaks[i+1]]
  glm::ivec3 cells_{0};
  glm::bvec3 c0_{false};                        // order-2 axes
  std::vector<std::array<double, 6>> m_;       // per cell: uu, vv, ww, uv, uw, vw
};

// The bound on ε_{F,T} of the parameter triangle (a, b, c), world units; +∞ when it crosses a C⁰ knot plane.
double triangle_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c, ErrorBound method = ErrorBound::best);

// ε_{F,T} measured: ‖F(T(s,t)) − T_F(s,t)‖ on the barycentric grid of `n` steps per edge, the worst sample refined on
// two finer grids around it (for checking the bounds and their tightness; a lower bound of ε, not a bound on it).
double triangle_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, int n = 24);

}  // namespace trispline::core
