// trispline::core global DFFD — a discontinuous FFD that splits an object around static obstacles and re-forms it
// behind them (seed §6.3.1, Fig. 6.1, 6.4, 6.10, 6.11).
//
// Construction (build_global_dffd), in the seed's order:
//  1. The lattice box B: the obstacles' bounding box, grown along u (the travel axis) by `margin` on both sides and
//     along v, w to contain the object too (so the object's part that must split is inside). E maps B onto [0,1]³
//     (u = axis, w = w_axis, v the remaining world axis, det E > 0).
//  2. A uniform lattice: clamped uniform knot vectors of the given order and control counts, control points at
//     E⁻¹(Greville abscissae), so F is exactly E⁻¹ (the identity of B) before any change.
//  3. For each obstacle O_i: `order` knots at its centre of mass u_0i (a C⁻¹ break, planes F⁻/F⁺; Def. 6), and
//     order − 1 knots in v at O_i's v-extremes (C⁰ there, Fig. 6.4), unless already that high.
//  4. Projection: for every (j, k), the F⁻ and F⁺ control points are moved along u onto the boundary curves
//     C⁻(v_j), C⁺(v_j) of O_i ∩ W_k (W_k: the plane w = w_k through the control row; found exactly by casting
//     rays along ±u through the obstacle's mesh, Embree) — the near and far faces of the cross-section, minus /
//     plus `clearance`.
//  5. Propagation: each displacement V± spreads to the control points behind F⁻ (resp. ahead of F⁺) along u as
//     κ(d)·V±, d the u-distance between the control points (world units), κ a truncated Gaussian (σ = width/3,
//     shifted and rescaled so κ(0) = 1 and κ(width) = 0) or the quadratic B-spline N₂ scaled to support
//     [−width, width] with κ(0) = 1. The lattice's first and last u-planes never move (F stays E⁻¹ on B's faces).
//  6. Fold-over check (seed Theorem 6): along every (j, k) the u-components of the control points must increase
//     (coincident F⁻/F⁺ allowed); then det J > 0. Violations are rejected (or reported, fold = warn).
//  7. Stitching (openings = stitch, §6.3.2): the control points of both discontinuity planes in the rows the
//     obstacle opened move to the level w = w_s, the mean w of the object's vertices on the cut (at the given
//     offset); the other rows are closed already (F⁻ = F⁺). With openings cap or stitch both lattices are kept in
//     rig.seam (dffd.animate keys the seam between them); rig.lattice is the one `openings` names.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/dffd/dffd_rig.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// A construction error that names the offending parameter (the dffd.split field).
struct DffdBuildError : std::invalid_argument {
  DffdBuildError(const std::string& what, std::string field_name)
      : std::invalid_argument(what), field(std::move(field_name)) {}
  std::string field;
};

enum class DffdKernel { gaussian, bspline };

// κ(d) of step 5: 1 at d = 0, 0 for |d| ≥ width (world units). Throws std::invalid_argument if width ≤ 0.
double dffd_kernel(DffdKernel kernel, double d, double width);

struct DffdObstacle {
  std::string name;    // scene object id (messages, display)
  TriMesh world_mesh;  // world units, closed for exact cross-sections
};

struct GlobalDffdParams {
  int axis = 0;                   // world axis (0 = x, 1 = y, 2 = z) of the lattice's u: the travel direction
  int w_axis = 1;                 // world axis of the lattice's w (the slicing planes W_k are orthogonal to it)
  glm::ivec3 order{3, 3, 3};      // order (= degree + 1) per lattice axis u, v, w; 2..6
  glm::ivec3 controls{12, 8, 8};  // control points per lattice axis before knot insertion; order..64
  DffdKernel kernel = DffdKernel::gaussian;
  double kernel_width = 0.0;  // world units, > 0 (the propagation reach along u)
  DffdOpenings openings = DffdOpenings::cap;
  bool reject_fold = true;  // false: keep a folding lattice and report where (fold = warn)
  double margin = -1.0;     // world units along u on both sides of the obstacles; < 0: 1.05 × kernel_width
  double clearance = 0.0;   // world units kept between the wrapped object and the obstacle, ≥ 0
  double eps = 1e-6;        // parameter units, cut vertices at u0 ∓ eps
  std::optional<Aabb> box;  // explicit lattice box (world); every obstacle must lie inside it
  glm::dvec3 offset{0.0};   // the object's parameter offset at t = 0 (for w_s)
};

// A control point that breaks u-monotonicity: P(i+1, j, k).u ≤ P(i, j, k).u (seed Theorem 6).
struct DffdFold {
  glm::ivec3 index{0};       // (i, j, k) of the first of the pair
  glm::dvec3 position{0.0};  // world position of P(i, j, k)
};

struct GlobalDffd {
  DffdRig rig;                       // lattice, embedding, params of the object, discontinuities (sorted by u0)
  Aabb box;                          // the lattice box B, world units
  std::vector<DffdFold> folds;       // empty unless reject_fold is false and the lattice folds
  std::size_t projected_points = 0;  // F⁻/F⁺ control points whose ray hit their obstacle
  std::size_t v_knots = 0;           // knots inserted in v at obstacle extremes
  double max_displacement = 0.0;     // world units, largest |V±|
  std::vector<double> w_s;           // stitching level per discontinuity (stitch only), parameter units
};

// Builds the DFFD of `object_world` (#V world rest positions with triangles) around `obstacles` (seed §6.3.1).
// Throws DffdBuildError with field: "axis"/"w_axis" (same or out of range), "order", "controls", "kernel_width"
// (≤ 0, non-finite; or a fold-over when reject_fold — the message names the count and the first (i,j,k) and world
// position), "obstacles" (none, an empty mesh, two centres too close to separate, a centre outside the domain),
// "box" (an obstacle not inside the explicit box: "obstacle larger than the lattice"), "margin", "clearance".
GlobalDffd build_global_dffd(const TriMesh& object_world, const std::vector<DffdObstacle>& obstacles,
                             const GlobalDffdParams& params);

// Finds the discontinuity of F at u0 on `axis` (knot multiplicity = order): plane indices as in
// insert_discontinuity. Throws std::invalid_argument if u0 is not a C⁻¹ break of that axis.
Discontinuity find_discontinuity(const TrivariateBSpline<glm::dvec3>& F, int axis, double u0);

}  // namespace trispline::core
