// trispline::core::TrivariateBSpline<T> — the tensor-product trivariate B-spline function
//   F(u,v,w) = Σ_i Σ_j Σ_k P_ijk B_i(u) B_j(v) B_k(w)                         (seed Eq. 2.1)
// with independent knot vector, order (= degree + 1) and control count per axis; T = double (scalar fields,
// ch. 7 volumes) or glm::dvec3 (FFD: the control lattice).
// Control points are stored u fastest: index(i,j,k) = i + l·(j + m·k), with (l,m,n) = control_counts().
// Parameters outside a knot vector's domain are clamped to it. Periodic axes (KnotVector::periodic_uniform, seed
// Fig. 4.5) store only period() control points (control_counts() gives the stored counts), use control i mod period
// and wrap parameters (t − ⌊t⌋) instead of clamping; F(u + 1, v, w) = F(u, v, w) there, C^(p−1) across the seam.
// Source: Piegl & Tiller ch. 3 generalised to three variables; knot insertion P&T A5.3 per axis.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core {

template <class T>
class TrivariateBSpline {
 public:
  // control_points: #(l·m·n), u fastest, (l,m,n) = KnotVector::stored_control_count() per axis (the period on a
  // periodic axis). Throws std::invalid_argument on count mismatch / non-finite values.
  TrivariateBSpline(KnotVector ku, KnotVector kv, KnotVector kw, std::vector<T> control_points);

  const KnotVector& knots(int axis) const { return k_[axis]; }  // axis 0 = u, 1 = v, 2 = w
  glm::ivec3 control_counts() const;                            // (l, m, n) stored (period on periodic axes)
  glm::ivec3 orders() const;                                    // order per axis (= degree + 1)
  std::size_t index(int i, int j, int k) const;
  const T& control_point(int i, int j, int k) const { return cps_[index(i, j, k)]; }
  T& control_point(int i, int j, int k) { return cps_[index(i, j, k)]; }
  const std::vector<T>& control_points() const { return cps_; }
  std::vector<T>& control_points() { return cps_; }

  // uvw is clamped to the domain (wrapped on periodic axes) per axis; a NaN component throws std::invalid_argument.
  T eval(const glm::dvec3& uvw) const;

  struct FirstDerivatives {
    T value;
    std::array<T, 3> d;  // ∂F/∂u, ∂F/∂v, ∂F/∂w
  };
  FirstDerivatives eval_first(const glm::dvec3& uvw) const;

  struct SecondDerivatives {
    T value;
    std::array<T, 3> d;                  // first partials
    std::array<std::array<T, 3>, 3> dd;  // dd[a][b] = ∂²F/∂a∂b (symmetric)
  };
  SecondDerivatives eval_second(const glm::dvec3& uvw) const;

  // Boehm knot insertion of t along `axis`, `times` times (capped at C^-1). F unchanged as a function.
  // Throws std::invalid_argument on a periodic axis (a periodic knot vector stays uniform; not supported).
  void insert_knot(int axis, double t, int times = 1);
  // Bézier extraction: all interior knots raised to multiplicity = order in every axis, so each cell of the
  // result is one Bézier trivariate. F unchanged as a function. Throws std::invalid_argument if any axis is
  // periodic (the result could not stay periodic).
  TrivariateBSpline<T> bezier_extracted() const;
  // The same function with every periodic axis unwrapped to an ordinary (floating) knot vector over one period (its
  // control points repeated as the periodic basis uses them); *this when no axis is periodic. Same domain.
  TrivariateBSpline<T> periodic_unwrapped() const;

 private:
  std::array<KnotVector, 3> k_;
  std::vector<T> cps_;
};

// Jacobian of a vector-valued trivariate: columns are ∂F/∂u, ∂F/∂v, ∂F/∂w (glm is column-major: J[c] = column c).
glm::dmat3 jacobian(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& uvw);
double jacobian_determinant(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& uvw);

extern template class TrivariateBSpline<double>;
extern template class TrivariateBSpline<glm::dvec3>;

}  // namespace trispline::core
