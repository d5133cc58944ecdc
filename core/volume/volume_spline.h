// trispline::core::VolumeSpline — a scalar volume as a trivariate tensor-product B-spline D(x) (seed Eq. 7.1).
//
// Uniform knots of spacing 1 in index space, the same order k (= degree + 1, 2…4) on every axis. Control point
// (i, j, l) sits at its Greville abscissa, the index-space point (i, j, l): D(x) = Σ P_ijl B_k(x − i) B_k(y − j)
// B_k(z − l) with B_k the centred cardinal B-spline of order k. Control points outside the grid repeat the nearest
// boundary sample (clamped indices), so D is defined on the whole grid box [0, nx−1] × [0, ny−1] × [0, nz−1] — the
// same box, in the same world coordinates, as the voxels. Control points are the samples themselves (the seed's
// choice: D approximates the data and smooths noise) or, with `interpolate`, the coefficients of the interpolating
// spline (D passes through every sample: the B-spline prefilter, Unser 1999, solved exactly per grid line).
//
// Knot spans (cells): for even k the knots are the integers and span s covers [s, s+1], s = 0…n−2; for odd k the knots
// are the half-integers and span s covers [s − ½, s + ½] ∩ [0, n−1], s = 0…n−1. Span s of order k is weighted by the
// control points first_control(s) … first_control(s) + k − 1 (clamped into the grid).
//
// Units: values in the volume's units (HU for CT); positions in index space unless a name says world (millimetres).
// Derivatives are per index unit; world_gradient converts. Deterministic: no threads, no reordering.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/volume/scalar_volume.h"

namespace trispline::core {

// Value, gradient and Hessian of D at one index-space point (per index unit).
struct VolumeJet {
  double value = 0.0;
  glm::dvec3 gradient{0.0};  // ∂D/∂x, ∂D/∂y, ∂D/∂z
  glm::dmat3 hessian{0.0};   // hessian[a][b] = ∂²D/∂a∂b (symmetric)
};

class VolumeSpline {
 public:
  // Throws std::invalid_argument: order outside 2…4, or scalar_volume_error(volume) non-empty.
  VolumeSpline(const ScalarVolume& volume, int order = 4, bool interpolate = false);

  int order() const { return order_; }
  bool interpolating() const { return interpolate_; }
  const std::array<int, 3>& dims() const { return dims_; }
  // Control lattice: dims[0]·dims[1]·dims[2] coefficients, x fastest (the samples, or the prefiltered coefficients).
  const std::vector<float>& control_points() const { return control_; }
  float control(int i, int j, int l) const;  // clamped indices
  const glm::dmat4& index_to_world() const { return index_to_world_; }
  const glm::dmat4& world_to_index() const { return world_to_index_; }
  // Upper bound of D's range over the domain: min/max over all control points (convex hull property).
  double control_min() const { return control_min_; }
  double control_max() const { return control_max_; }

  // Knot spans per axis (see the header comment) and the span containing t (clamped to the domain).
  int span_count(int axis) const { return span_count_[axis]; }
  int span_of(int axis, double t) const;
  // Start of span s in index space (unclipped: −½ for the first span of an odd order).
  double span_begin(int s) const { return s + shift_; }
  int first_control(int s) const { return s - (order_ - 1) / 2; }

  // D at an index-space point clamped into the domain.
  double value(const glm::dvec3& x) const;
  // D, ∇D and the Hessian at an index-space point clamped into the domain.
  VolumeJet jet(const glm::dvec3& x) const;
  // ∇D per millimetre from ∇D per index unit: (A⁻¹)ᵀ g with A the linear part of index_to_world.
  glm::dvec3 world_gradient(const glm::dvec3& index_gradient) const;

  // Bernstein (Bézier) coefficients of D on cell (s0, s1, s2) over the whole unclipped span (knot insertion at every
  // interior knot, seed §7.3.2): order³ values, first axis fastest, out[a + k·(b + k·c)].
  void bezier_coefficients(int s0, int s1, int s2, double* out) const;
  // The order × order matrix of that knot insertion on one axis: Bézier coefficient a of a span = Σ_r m[a·order + r]
  // · control point first_control(s) + r.
  const std::array<double, 16>& to_bezier() const { return to_bezier_; }

 private:
  int order_ = 4;
  bool interpolate_ = false;
  std::array<int, 3> dims_{0, 0, 0};
  std::array<int, 3> span_count_{0, 0, 0};
  double shift_ = 0.0;  // span_begin(s) − s: 0 for even orders, −½ for odd
  std::vector<float> control_;
  glm::dmat4 index_to_world_{1.0}, world_to_index_{1.0};
  glm::dmat3 gradient_to_world_{1.0};
  double control_min_ = 0.0, control_max_ = 0.0;
  std::array<double, 16> to_bezier_{};  // order × order: Bézier coefficient a = Σ_r to_bezier_[a·order + r] P_r
};

// The centred uniform B-spline basis of order k on one span: w[r] (r = 0…k−1) weights control first_control(s) + r at
// local coordinate x ∈ [0,1] (x = t − span_begin(s)); dw and d2w (may be null) are the first and second derivatives.
void uniform_bspline_weights(int order, double x, double* w, double* dw, double* d2w);

// Calls f(std::integral_constant<int, K>{}) with K = `order` (a VolumeSpline's order, 2…4; anything else reads as 4):
// the dispatch from a spline's run-time order to the kernels compiled per order.
template <class F>
decltype(auto) with_volume_order(int order, F&& f) {
  switch (order) {
    case 2:
      return f(std::integral_constant<int, 2>{});
    case 3:
      return f(std::integral_constant<int, 3>{});
    default:
      return f(std::integral_constant<int, 4>{});
  }
}

}  // namespace trispline::core
