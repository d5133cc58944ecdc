// trispline::core refine — adaptive refinement of an FFD-embedded mesh so that its deformed edges follow F
// (seed §2.4.2, Eq. 2.6, Fig. 2.9–2.10).
//
// Mapping only the vertices through F leaves every deformed edge straight: the edge (a,b) shows the chord
// L(t) = (1−t)·F(E(a)) + t·F(E(b)) instead of the curve E_p(t) = F(E(a + t(b−a))). Refinement splits the edges whose
// chord strays from the curve by more than a tolerance (world units), in rounds, keeping the mesh conforming:
//   1. every edge is measured once (edges are keyed by the *positions* of their ends, so a crease stored twice with
//      split normals/uvs is measured and split identically on both sides — no cracks);
//   2. marked edges are split at a parameter t of the edge;
//   3. each triangle is re-triangulated by its number of split edges (red-green: 1 → 2, 2 → 3, 3 → 4), keeping its
//      winding; the 2-split quad takes the diagonal that is shorter after deformation;
//   4. repeat until no edge is over tolerance, or max_iterations / max_triangles stops it (reported).
// Criteria:
//   Midpoint (Chua & Neumann 1998, seed Eq. 2.6): error = |F(E((a+b)/2)) − (F(E(a)) + F(E(b)))/2|, split at t = 1/2.
//   Greville (seed §2.4.2): E_p is a piecewise polynomial of degree D = Σ_axes (order − 1) (= 3(o−1) for equal
//     orders), its pieces delimited by the knot planes (and clamping/wrapping planes) the edge crosses. On each
//     piece the Bézier control points c_j of E_p are computed exactly (up to rounding) by interpolating D+1 samples
//     at Chebyshev–Lobatto nodes (a polynomial of degree ≤ D is determined by D+1 values). The composed curve is the
//     B-spline made of these pieces; c_j's Greville abscissa (nodal value) is t0 + (j/D)(t1 − t0). The error is
//     max_j dist(c_j, chord segment F(E(a))F(E(b))) — the seed's distance from the chord (the segment rather than
//     its line, which is ≥ and stays a bound): by the convex hull property every point of E_p lies within that
//     distance of the deformed straight edge. The edge is split at the nodal value of the farthest control point,
//     clamped to [min_split, 1 − min_split] (no sliver triangles).
// Certified mode (RefineError::bound, seed §3.2.3 BoundMeshError): instead of measuring edges, every triangle gets its
// certified deformation-error bound (deformation_bounds.h: the best of Theorem 4's right-triangle bound and the
// smallest-enclosing-circle bound); each triangle over tolerance is split — Midpoint: the seed's RefineTriangle (all
// three edges at their midpoints); Greville: all three at the Greville criterion's split points; Best: per triangle
// the 1 → 4 split or the bisection of its longest edge (Rivara), at midpoints, whichever's children are expected to
// need the fewest triangles (bounds scale with size², so a child with bound β needs ~β/δ) — the rest conformingly,
// until every triangle's bound is within tolerance; then the refined mesh certifies it (stats.max_triangle_bound ≤
// tolerance, stopped_by "converged").
// New vertices interpolate position, FFD parameters (the embedding is affine), normal (re-normalised) and uv
// linearly along the edge, in the canonical direction of the edge, so equal inputs give bit-identical outputs.
// The rest mesh may be given in any space that is an affine image of the embedded world rest space (object space,
// say): splits are chosen from the parameters and F only, and affine maps commute with linear interpolation.
// Deterministic: same input → same output, bit for bit (per-edge work is independent; order is triangle order).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/ffd/ffd.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Best: certified refinement only — each triangle over tolerance takes, of the 1 → 4 split and the bisection of its
// longest edge (both at midpoints), the one whose children are expected to need the fewest triangles.
enum class RefineCriterion { Midpoint, Greville, Best };
// What is held to the tolerance: each edge's measure (the criterion's), or each triangle's certified error bound.
enum class RefineError { edge, bound };

// "midpoint" / "greville" / "best" ↔ enum. parse throws std::invalid_argument on any other name.
RefineCriterion parse_refine_criterion(const std::string& name);
const char* refine_criterion_name(RefineCriterion c);

struct RefineOptions {
  double tolerance = 0.01;  // world units, > 0 and finite
  RefineCriterion criterion =
      RefineCriterion::Greville;  // where an edge is split (and, with RefineError::edge, what marks it)
  RefineError error = RefineError::edge;
  int max_iterations = 16;                // split rounds, ≥ 0
  std::size_t max_triangles = 2'000'000;  // a round that would exceed it is not applied; ≥ #F of the input
  double min_split = 0.1;                 // Greville split parameter clamped to [min_split, 1 − min_split]; (0, 0.5]
  glm::dvec3 param_offset{0.0};           // F is evaluated at params + param_offset (SceneObject::param_offset)
};

struct RefineStats {
  std::size_t triangles_before = 0, triangles_after = 0;
  std::size_t vertices_before = 0, vertices_after = 0;
  int iterations = 0;                // split rounds applied
  double max_midpoint_error = 0.0;   // Eq. 2.6 over the final edges, world units
  double max_deviation_bound = 0.0;  // Greville measure (control points' distance from the chord), final edges
  double max_triangle_bound = 0.0;   // RefineError::bound: the largest certified triangle bound, final triangles
                                     // (+∞ where a triangle crosses a C⁰ knot plane); 0 otherwise
  bool stopped_by_budget = false;    // edges were still over tolerance when a limit stopped the rounds
  std::string stopped_by;            // "converged", "max_iterations" or "max_triangles"
};

struct RefineResult {
  TriMesh mesh;                    // refined rest mesh, same space as the input; old vertices first, in order
  std::vector<glm::dvec3> params;  // #V × 3, FFD parameters of mesh's vertices (without param_offset)
  RefineStats stats;
};

// Refines `rest` (#V vertices, #F triangles CCW; normals and uvs optional, kept and interpolated) bound to
// `binding` (binding.params #V × 3 parameters, binding.lattice = F). Throws std::invalid_argument on a params/vertex
// count mismatch, out-of-range indices, or bad options (tolerance ≤ 0 or non-finite, max_iterations < 0,
// max_triangles < #F, min_split outside (0, 0.5], criterion Best without RefineError::bound).
RefineResult refine_for_ffd(const TriMesh& rest, const FfdBinding& binding, const RefineOptions& options);

// Edge measures, exposed for tests (pa, pb: parameters of the edge's ends, offset already added).
// Eq. 2.6 midpoint error, world units.
double ffd_edge_midpoint_error(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb);
struct EdgeGreville {
  double bound = 0.0;  // max_j dist(c_j, chord segment), world units (≥ max_t dist(E_p(t), chord segment))
  double t = 0.5;      // nodal value of the farthest control point, in [0,1] (unclamped)
};
EdgeGreville ffd_edge_greville(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb);
// Bézier control points of E_p on its polynomial pieces: pieces #P+1 breakpoints in [0,1], ctrl #P·(D+1), D = degree.
void ffd_edge_bezier(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb,
                     std::vector<double>& breaks, std::vector<glm::dvec3>& ctrl, int& degree);

}  // namespace trispline::core
