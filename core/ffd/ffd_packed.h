// trispline::core::FfdPackedLattice — a control lattice flattened into float tables, the single data source of the
// float backends (cpu_fast, glsl_compute, glsl_vertex), so all of them evaluate the same function the same way.
//
// Per axis a (0 = u, 1 = v, 2 = w), built from SpanBasis<float> (power basis per non-empty span, P&T §2.5):
//   * a parameter t is first wrapped (periodic axis: t − ⌊t⌋) or clamped (otherwise) to [domain_min, domain_max];
//   * span slot s: uniform_spans → s = clamp(⌊(t − domain_min)·inv_uniform_len⌋, 0, S−1) corrected by one against
//     span_begin (rounding next to a knot); otherwise the last s with span_begin[s] ≤ t (binary search);
//   * local x = (t − span_begin[s])·inv_span_len[s] ∈ [0,1];
//   * basis r ∈ [0, order): N_r(x) = Σ_k coef[(s·order + k)·order + r]·x^k  (Horner); dN_r/dt =
//   (dN_r/dx)·inv_span_len[s];
//   * control index along the axis: first_index[s] + r, taken modulo `axes[a].count` on a periodic axis.
// Control point (i,j,k) (u fastest) is control_points[4·(i + l·(j + m·k)) + c] for c = x,y,z (c = 3 is 0), stored
// relative to `centre` (the lattice's bounding-box centre) so float rounding stays relative to the lattice size.
// Position = centre + Σ N_i N_j N_k P_ijk; normal ∝ cof(J·A)·n with A = embedding_linear.
// Float accuracy: accumulate Σ N·(P − P_first) and add P_first afterwards (P_first = the control point of basis
// (0,0,0) of the vertex's support). It is the same function (Σ N = 1, Σ dN/dt = 0) but keeps the derivative sums
// from cancelling on lattices with many spans (dN/dt grows with the span count): on a 60³ cubic lattice the normal
// error drops from 1.1e-4 to 1.6e-5 rad (cpu_fast gather kernel, tests/core/ffd).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "core/ffd/ffd.h"

namespace trispline::core {

struct FfdPackedAxis {
  int order = 0;               // 2..4 (degree + 1)
  int count = 0;               // stored control points along the axis (the period on a periodic axis)
  bool periodic = false;       // wrap parameters and control indices
  bool uniform_spans = false;  // O(1) span lookup valid
  float domain_min = 0, domain_max = 1;
  float inv_uniform_len = 1;        // span_count / (domain_max − domain_min)
  std::vector<float> span_begin;    // #S + 1 (last entry = domain_max)
  std::vector<float> inv_span_len;  // #S
  std::vector<int> first_index;     // #S, index of basis r = 0 (before the periodic modulo)
  std::vector<float> coef;          // #S · order · order, [slot][power k][basis r]
  int span_count() const { return static_cast<int>(inv_span_len.size()); }
};

struct FfdPackedLattice {
  std::array<FfdPackedAxis, 3> axes;
  std::vector<float> control_points;        // #controls × 4, u fastest, relative to centre, world units
  glm::dvec3 centre{0.0};                   // world units
  glm::dvec3 bbox_min{0.0}, bbox_max{0.0};  // bounding box of the control points (max_err_rel's denominator)
  glm::mat3 embedding_linear{1.0f};         // A (column-major), for normals

  // Throws std::invalid_argument if an order is outside 2..4.
  static FfdPackedLattice build(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding);
  double bbox_diagonal() const { return glm::length(bbox_max - bbox_min); }
};

}  // namespace trispline::core
