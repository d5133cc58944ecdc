// trispline::core fast FFD path — single precision, per-span power-basis tables, fixed-order kernels.
//
// Same function as the reference ffd_evaluate (ffd.h), checked against it in tests/core/deform (position error
// ≤ 1e-5 × lattice bounding-box diagonal). Built for throughput on big meshes (benchmark: `trispline bench ffd`):
//   * per axis, basis functions come from SpanBasis<float> (core/spline/span_basis.h): per-span power-basis
//     polynomials in the local coordinate (Horner, no recurrence), O(1) span lookup for uniform interior spans and
//     a binary search otherwise;
//   * control points are stored as float xyz + pad (relative to the lattice's bounding-box centre, which keeps float
//     rounding relative to the lattice size), so the inner tensor contraction is a 4-wide SIMD multiply-add;
//   * kernels are templates on the orders (2..4 per axis, all 27 combinations); other orders fall back to the double
//     reference path and round its result.
// Parallel over vertex blocks (oneTBB); every vertex is independent, so the output does not depend on the thread
// count either (bit-identical on one machine and build).
// Source: Sederberg & Parry 1986; seed Eq. 2.1; power-basis span tables as in Piegl & Tiller §2.5 / ch. 6.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/deform/ffd.h"
#include "core/spline/span_basis.h"

namespace trispline::core {

// Three float arrays of equal length (structure of arrays): #N × 3.
struct FloatSoA3 {
  std::vector<float> x, y, z;
  std::size_t size() const { return x.size(); }
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  static FloatSoA3 from(const std::vector<glm::dvec3>& v);  // rounds to float
  std::vector<glm::dvec3> to_dvec3() const;
};

// A lattice and embedding prepared for ffd_evaluate_fast. Rebuild after the lattice changes (cheap: O(#controls)).
class FfdFastLattice {
 public:
  // Copies what it needs from F. Throws std::invalid_argument if an axis has order < 2.
  FfdFastLattice(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding);

  const SpanBasis<float>& basis(int axis) const { return axes_[axis]; }  // axis 0 = u, 1 = v, 2 = w
  bool has_kernel() const;  // true when all orders are in 2..4 (otherwise the double fallback runs)

 private:
  friend struct FfdFastAccess;
  std::array<SpanBasis<float>, 3> axes_;
  std::array<std::vector<float>, 3> inv_len_;  // per axis, per span slot: 1 / span length (chain rule)
  glm::ivec3 counts_{0};
  std::vector<float> cps_;  // #controls × 4 (x, y, z, 0), relative to centre_
  glm::dvec3 centre_{0.0};
  std::array<float, 9> linear_{};                          // embedding A, column-major
  std::optional<TrivariateBSpline<glm::dvec3>> fallback_;  // copy of F when an order is outside 2..4
  Embedding embedding_;
};

// Positions only. params #N × 3 parameter-domain points; out_positions resized to #N, world units.
void ffd_evaluate_fast(const FfdFastLattice& lattice, const FloatSoA3& params, FloatSoA3& out_positions);

// Positions and exact normals n' ∝ cof(J_F·A)·n (unit; the rest normal where degenerate).
// rest_normals #N × 3 unit, world rest space. Throws std::invalid_argument on size mismatch.
void ffd_evaluate_fast(const FfdFastLattice& lattice, const FloatSoA3& params, const FloatSoA3& rest_normals,
                       FloatSoA3& out_positions, FloatSoA3& out_normals);

}  // namespace trispline::core
