// trispline::core DffdRig — a mesh bound to a discontinuous FFD (seed ch. 6): the lattice with its C⁻¹ breaks, the
// embedding, and how the openings are treated. Evaluating it splits the mesh at every break *at evaluation time*
// (seed §6.3.2), because an object that moves through the lattice (its parameter offset animated, Fig. 6.10) is cut
// at a different place of its surface in every frame.
//
// Pipeline of dffd_apply, per evaluation (CPU, double, deterministic):
//   1. p = params + offset for every rest vertex (offset: SceneObject::offset_at(t), parameter units);
//   2. for every discontinuity in order: split_mesh_at_parameter at its u0 (edges and faces crossing it are cut
//      exactly, new vertices pushed to u0 ∓ eps), then for openings = cap | stitch the cross-section loops are
//      capped (cap_split_openings, CGAL constrained Delaunay);
//   3. x' = F(p) where p lies in the parameter domain [0,1]³, otherwise x' = E⁻¹(p) (identity_outside: the global
//      DFFD of seed §6.3.1 spans only the obstacles' region; its lattice starts as the exact identity of its box, so
//      the two agree on the box's faces), normals mapped through cof(J_F·A) (as ffd_apply) or kept outside.
// openings = stitch differs from cap only in the lattice (dffd.split moved the F⁻/F⁺ control points to the
// stitching level w_s, seed §6.3.2), so the caps it adds are flattened onto the seam: watertight and closed-looking.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/deform/dffd.h"
#include "core/deform/ffd.h"
#include "core/mesh/tri_mesh.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// How the openings left by the splits are treated (dffd.split "openings").
enum class DffdOpenings { open, stitch, cap };
const char* dffd_openings_name(DffdOpenings o);  // "open" | "stitch" | "cap"

struct DffdRig {
  TrivariateBSpline<glm::dvec3> lattice;       // world units; knots hold the C⁻¹ breaks (multiplicity = order)
  Embedding embedding;                         // world rest space → parameter domain ([0,1]³ = the lattice box)
  std::vector<glm::dvec3> params;              // #V × 3: E(world rest position) of every rest vertex
  std::vector<Discontinuity> discontinuities;  // applied in this order (dffd.split: sorted by u0)
  DffdOpenings openings = DffdOpenings::open;
  double eps = 1e-6;                           // parameter units: cut vertices sit at u0 ∓ eps
  bool identity_outside = true;                // outside [0,1]³ map by E⁻¹ instead of clamping
  // Display and report (not used by the evaluation):
  std::vector<std::string> obstacles;          // obstacle object ids (dffd.split)
  std::vector<glm::dvec3> fold_points;         // world positions of control points that broke u-monotonicity
                                               // (seed Theorem 6) when dffd.split ran with "fold":"warn"
};

// What one evaluation did.
struct DffdApplyStats {
  std::size_t cut_edges = 0;         // input edges cut, all discontinuities together
  std::size_t cap_loops = 0;         // cross-section loops capped
  std::size_t open_chains = 0;       // chains left uncapped (mesh not closed at a cut)
  std::size_t cap_triangles = 0;
  std::size_t outside_vertices = 0;  // vertices mapped by the identity (outside [0,1]³)
};

// Steps 1–2 only: the split (and capped) rest mesh with its parameters (offset included) and sides of the last
// split; what dffd_apply deforms. Same errors as dffd_apply.
MeshSplit dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                     DffdApplyStats* stats = nullptr);

// Evaluates the rig on `rest_world` (world rest mesh with normals, #V = rig.params.size()) at parameter offset
// `offset`: the split (and capped) mesh, deformed. Output vertices: the #V input vertices first, then the split's
// new ones; face_material kept (caps get kMaterialInside). Deterministic.
// Throws std::invalid_argument: params.size() != #V, non-finite offset.
TriMesh dffd_apply(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                   DffdApplyStats* stats = nullptr);

}  // namespace trispline::core
