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
// Because the two share the split and the caps, the seam can be keyed between them (dffd.animate, DffdSeam): at
// stitch weight s the control points are (1 − s)·open + s·stitched, so every vertex moves on the straight line
// between its capped and its stitched position (F is linear in its control points) — a per-vertex morph of one
// topology, exact at s = 0 and s = 1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/dffd/dffd.h"
#include "core/dffd/dffd_cap.h"
#include "core/ffd/ffd.h"
#include "core/mesh/tri_mesh.h"
#include "core/spline/keyframes.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// How the openings left by the splits are treated (dffd.split "openings").
enum class DffdOpenings { open, stitch, cap };
const char* dffd_openings_name(DffdOpenings o);  // "open" | "stitch" | "cap"

// The two lattices a keyed seam blends (seed §6.3.2): every control point with the openings as the obstacles left
// them (capped, s = 0) and with the opened rows of both discontinuity planes moved to the stitching level w_s
// (s = 1). World units, n_u·n_v·n_w points each in the lattice's order (TrivariateBSpline::control_points()).
struct DffdSeam {
  std::vector<glm::dvec3> open_points;
  std::vector<glm::dvec3> stitched_points;
};

struct DffdRig {
  TrivariateBSpline<glm::dvec3> lattice;       // world units; knots hold the C⁻¹ breaks (multiplicity = order)
  Embedding embedding;                         // world rest space → parameter domain ([0,1]³ = the lattice box)
  std::vector<glm::dvec3> params;              // #V × 3: E(world rest position) of every rest vertex
  std::vector<Discontinuity> discontinuities;  // applied in this order (dffd.split: sorted by u0)
  DffdOpenings openings = DffdOpenings::open;
  double eps = 1e-6;             // parameter units: cut vertices sit at u0 ∓ eps
  bool identity_outside = true;  // outside [0,1]³ map by E⁻¹ instead of clamping
  // Display and report (not used by the evaluation):
  std::vector<std::string> obstacles;   // obstacle object ids (dffd.split)
  std::vector<glm::dvec3> fold_points;  // world positions of control points that broke u-monotonicity
                                        // (seed Theorem 6) when dffd.split ran with "fold":"warn"
  // The keyed seam (dffd.animate; scene_at_time freezes it with dffd_rig_at). Both seam states: openings cap or
  // stitch; null with open (there the caps are missing: another topology).
  std::shared_ptr<const DffdSeam> seam;
  // The stitch weight s over scene time (dffd.animate; .offset.x, 0 capped open, 1 stitched), sorted by time. Empty:
  // the lattice as built. With keys the lattice is the blend at scene time 0 (what world_mesh shows).
  std::vector<OffsetKey> stitch_keys;
  bool stitch_animated() const { return stitch_keys.size() >= 2; }
};

// The stitch weight at `time_s`: the keys' value, or the built state (1 for openings = stitch, 0 otherwise) without
// keys.
double dffd_stitch_at(const DffdRig& rig, double time_s);

// Sets rig.lattice's control points to the seam blended at weight s: (1 − s)·open + s·stitched (exactly the open
// points at s = 0 and the stitched ones at s = 1; s outside [0, 1] extrapolates). Keys are kept.
// Throws std::invalid_argument: no seam (openings = open), seam sizes not the lattice's, non-finite s.
void dffd_set_stitch(DffdRig& rig, double s);

// `rig` as a still at `time_s`: the same pointer when its seam is not keyed, else a copy with the lattice blended at
// dffd_stitch_at(time_s) and no keys. Same errors as dffd_set_stitch.
std::shared_ptr<const DffdRig> dffd_rig_at(const std::shared_ptr<const DffdRig>& rig, double time_s);

// What one evaluation did.
struct DffdApplyStats {
  std::size_t cut_edges = 0;    // input edges cut, all discontinuities together
  std::size_t cap_loops = 0;    // cross-section loops capped
  std::size_t open_chains = 0;  // chains left uncapped (mesh not closed at a cut)
  std::size_t cap_triangles = 0;
  std::size_t outside_vertices = 0;  // vertices mapped by the identity (outside [0,1]³)
};

// Steps 1–2 only: the split (and capped) rest mesh with its parameters (offset included) and sides of the last
// split; what dffd_apply deforms. Same errors as dffd_apply.
MeshSplit dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                     DffdApplyStats* stats = nullptr, const CapTexturing& texturing = {});

// The same into `out`, whose buffers are reused (assigned, not reallocated, once they are large enough): one copy of
// the rest mesh per call, breaks outside the mesh's parameter range skipped, each cap built from the triangles its
// split touched. On error `out` is unspecified.
void dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, MeshSplit& out,
                DffdApplyStats* stats = nullptr, const CapTexturing& texturing = {});

// Step 3 only: deforms `split` (from dffd_split) into `out`. Triangles, uvs and face_material are swapped out of
// split.mesh (so both keep their buffers); positions / normals are evaluated into out's buffers in one parallel
// pass (ffd_evaluate_identity_outside when rig.identity_outside). Sets stats->outside_vertices.
// Throws std::invalid_argument: split.mesh and split.params disagree on #V, normals neither empty nor #V.
void dffd_deform(const DffdRig& rig, MeshSplit& split, TriMesh& out, DffdApplyStats* stats = nullptr);

// Evaluates the rig on `rest_world` (world rest mesh with normals, #V = rig.params.size()) at parameter offset
// `offset`: the split (and capped) mesh, deformed. Output vertices: the #V input vertices first, then the split's
// new ones; face_material kept (caps get kMaterialInside). `texturing` enabled: the caps get vertices of their own
// with planar uvs (cap_split_openings), appended after each split's new ones. Deterministic, and the same mesh bit
// for bit as dffd_split followed by dffd_deform (it runs as a fresh DffdFrameEvaluator, see below).
// Throws std::invalid_argument: params.size() != #V, non-finite offset, normals / uvs neither empty nor #V,
// face_material neither empty nor #F, a triangle index ≥ #V.
TriMesh dffd_apply(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                   DffdApplyStats* stats = nullptr, const CapTexturing& texturing = {});

// The cap texturing of an inside texture one repeat of which spans `texture_size` world units on the caps: per
// parameter axis k, |E⁻¹ e_k| (the world length of a parameter unit, rig.embedding) ÷ texture_size; caps refined to
// one uniform knot span of the finest axis, 1 ÷ max(#controls − order + 1) parameter units (CapTexturing::max_edge; the
// knot vectors of a global DFFD are uniform but for the C⁻¹ breaks). Throws
// std::invalid_argument: texture_size not finite and > 0, a singular embedding.
CapTexturing cap_texturing(const DffdRig& rig, double texture_size);

// Frame after frame evaluation of one rig (playback, recording, the bench): dffd_apply with its buffers kept
// between calls, so a warm evaluator allocates nothing, and with the deformation of the input vertices (whose
// parameters the split does not change, except on-plane ones, re-evaluated after) running on a worker while the
// split and caps are built. The result is bit-identical to dffd_apply's (each vertex depends only on its own
// parameter and rest normal). The returned mesh lives until the next evaluate(). Same errors as dffd_apply.
// Not thread-safe: one per object and thread.
class DffdFrameEvaluator {
 public:
  const TriMesh& evaluate(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                          DffdApplyStats* stats = nullptr, const CapTexturing& texturing = {});
  // The last evaluated mesh, moved out (the evaluator's output buffers start empty again).
  TriMesh take() { return std::move(mesh_); }

 private:
  MeshSplit split_;
  TriMesh mesh_;
  std::vector<glm::dvec3> base_;  // #V: params + offset of the input vertices
  std::vector<std::size_t> redo_;
  std::vector<glm::dvec3> redo_params_, redo_normals_, redo_pos_, redo_out_normals_;
};

}  // namespace trispline::core
