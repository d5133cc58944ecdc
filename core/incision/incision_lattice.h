// Internal to trispline_incision: the local lattice of one incision (seed Eq. 6.2) with its discontinuity, the
// opening as a displacement lattice, and point inversion (Newton on the un-opened F with a frame-guess fallback).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/incision/incision.h"

namespace trispline::core::incision_detail {

struct LocalLattice {
  IncisionParams params;
  glm::ivec3 controls{0};                // (l, m, n) of Eq. 6.2, before knot insertion
  double alpha = 0.0;                    // world units between control planes along S (Eq. 6.2)
  double beta = 0.0;                     // world units between control planes along N (Eq. 6.2)
  double half_height = 0.0;              // ⌊n/2⌋·β: the lattice reaches this far above the surface and below it
  double bottom_w = 0.0;                 // parameter w of the cut's bottom (depth below G along N)
  TrivariateBSpline<glm::dvec3> base;    // Eq. 6.2, no knots inserted (point inversion)
  TrivariateBSpline<glm::dvec3> split;   // base with `order` knots at u = 1/2 and order − 1 at w = bottom_w
  TrivariateBSpline<glm::dvec3> offset;  // displacement lattice D (same knots as split): F_open = split + offset
  // Eq. 6.2 is linear in i and k, so F(u,v,w) = Ĝ(v) + a(u)·Ŝ(v) + c(w)·N̂(v) with Ĝ = Σ_j B_j G_j, Ŝ = Σ_j B_j α S_j,
  // N̂ = Σ_j B_j β N_j, a(u) = Σ_i B_i (⌊l/2⌋ − i), c(w) = Σ_k B_k (⌊n/2⌋ − k): five curves instead of the volume.
  std::optional<BSplineCurve<glm::dvec3>> g_hat, s_hat, n_hat;
  std::optional<BSplineCurve<double>> a_of_u, c_of_w;
  // Samples of the frame along v for the inversion's initial guess (#K each).
  std::vector<double> sample_v;
  std::vector<glm::dvec3> sample_g, sample_s, sample_n, sample_t;  // G, unit S, N, T
  std::vector<double> sample_speed;                                // |G'(v)|, world units per unit v
};

// F(q) of the un-opened lattice (= base.eval(q)) through the five curves; with d: the three partials too.
glm::dvec3 eval_base(const LocalLattice& L, const glm::dvec3& q, glm::dvec3* d = nullptr);

// A located point: `param` is the Newton solution when `inside`, otherwise the frame's linear guess extended
// beyond [0,1]³ (u from the offset along S, v from the nearest sample plus the offset along T, w from the offset
// along N), used only to decide on which side of the cut sheet an outside end of a crossing edge lies.
struct Located {
  glm::dvec3 param{0.0};
  bool inside = false;
  bool fallback = false;  // inside, but Newton failed and the frame guess was used
};

// Builds the lattice (checks params; errors as incise()).
LocalLattice build_local_lattice(const IncisionFrame& frame, const IncisionParams& params);

// Parameters of world point x in the lattice (point inversion by damped Newton on `base`, seed §6.4).
Located invert_point(const LocalLattice& L, const glm::dvec3& x);

}  // namespace trispline::core::incision_detail
