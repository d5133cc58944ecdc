// trispline::core incisions (module core/incision, library trispline_incision) — local discontinuous FFD as a
// cutting tool (seed §6.4, Eq. 6.2, Fig. 6.5, 6.6, 6.8).
//
// A stroke of surface hit points gives the generator curve G(v) (least-squares B-spline), its unit tangent T(v)
// and the normal curve N(v) fitted to the surface normals at the hits; S = T × N. The local lattice of Eq. 6.2,
//   P_ijk = G_j + (⌊l/2⌋ − i)·α·S_j + (⌊n/2⌋ − k)·β·N_j,
// straddles the surface along the stroke (G at u = w = 1/2). `order` knots inserted at u = 1/2 make the C⁻¹
// discontinuity; the F⁻/F⁺ control planes and their neighbours along u are moved apart along ∓S by the kernel κ
// (the opening), tapering to zero at the cut's bottom (the depth) and at both ends of the stroke so the cut
// closes there. Mesh vertices inside the lattice's range are located in its parameter domain by point inversion
// (Newton on the un-opened F, with a fallback), faces crossing u = 1/2 are split, and the cut-depth walls are built
// in the shape of the tool so the surface stays a closed 2-manifold (seed §6.4, last paragraph).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/spline/bspline_curve.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

class RayCaster;
struct Camera;
enum class BuildQuality;

// Kernel κ of the opening along u (seed §6.3.1 kernels): weight of a control plane from its Greville distance
// d = |ū_i − 1/2| ∈ [0, 1/2] to the cut, 1 at the cut and exactly 0 at the lattice's u-boundaries (d = 1/2).
//   gaussian: (exp(−d²/(2σ²)) − exp(−1/(8σ²))) / (1 − exp(−1/(8σ²))), σ = 0.2
//   bspline:  quadratic B-spline, B₂(3d)/B₂(0) with B₂(x) = 3/4 − x² (|x| ≤ 1/2), (3/2 − |x|)²/2 (|x| ≤ 3/2)
enum class IncisionKernel { gaussian, bspline };

// User parameters of one incision (incision.draw fields).
struct IncisionParams {
  double width = 0.0;    // world units, > 0: the opening's reach across the cut (half-extent of the lattice in S)
  double depth = 0.0;    // world units, > 0: how deep below the surface the cut goes (along −N)
  double opening = 0.0;  // world units, ≥ 0: gap between the two cut faces at the surface, mid-stroke
  bool walls = true;     // build the cut-depth walls (kMaterialInside faces); false leaves the opening open
  int order = 3;         // order (= degree + 1) of the lattice in u, v, w; 2..4
  // Control counts (l, m, n) of Eq. 6.2 before knot insertion; 0 = default: l = 7, m = clamp(#hits/3, order, 24),
  // n = 5. l and n must be odd (the generator lies on the middle planes) and ≥ max(3, order); m in order..64.
  int controls_u = 0, controls_v = 0, controls_w = 0;
  IncisionKernel kernel = IncisionKernel::gaussian;
  int wall_rows = 4;  // rows of wall quads from each rim down to the bottom curve, 1..32
  double eps = 1e-6;  // parameter units: split vertices get u = 1/2 ∓ eps, in (0, 1e-3]
};

// The generator frame fitted to the stroke's surface hits.
struct IncisionFrame {
  std::vector<glm::dvec3> hits;        // #H × 3 world hit points used, in stroke order
  std::vector<glm::dvec3> normals;     // #H × 3 unit surface normals at the hits
  BSplineCurve<glm::dvec3> generator;  // G(v), v ∈ [0,1], world units (least squares, chord-length parameters)
  BSplineCurve<glm::dvec3> normal;     // N(v) (fitted, normalise when sampling)
};

// Fits the frame to `stroke_px` (#S × 2 viewport pixels of `camera`) cast against `surface` (first hits).
// Returns nullopt when fewer than two stroke points hit, the hits span no length or cannot be fitted (the stroke
// misses). Non-finite stroke points are skipped. Deterministic; cheap (one ray per stroke point).
std::optional<IncisionFrame> fit_incision_frame(const std::vector<glm::dvec2>& stroke_px, const Camera& camera,
                                                const RayCaster& surface);

// A RayCaster over only the triangles of `surface` (world units) that the rays through `stroke_px` (#S × 2 viewport
// pixels of `camera`) can hit: those whose projected bounding box, grown by 2 pixels, contains a stroke pixel, and
// every triangle with a vertex at or behind the eye. For those pixels its first hits are those of a caster over the
// whole mesh, and it builds in a fraction of the time (incision.draw; the editor keeps one caster per mesh instead).
RayCaster stroke_ray_caster(const TriMesh& surface, const Camera& camera, const std::vector<glm::dvec2>& stroke_px,
                            BuildQuality quality);

// Result of incise().
struct IncisionResult {
  TriMesh mesh;                           // the cut surface, world units; #V' ≥ #V (input vertices keep indices)
  TrivariateBSpline<glm::dvec3> lattice;  // the opened local lattice (display), world units
  std::size_t embedded_vertices = 0;      // input vertices located in the lattice (point inversion)
  std::size_t newton_fallbacks = 0;       // of those, located by the fallback
  std::size_t cut_edges = 0;              // input edges split
  std::size_t wall_faces = 0;             // kMaterialInside faces added
  // Diagnostics and display:
  std::size_t split_faces = 0;      // input triangles replaced by pieces (2 cut edges, or 1 = a tip face)
  std::size_t tips = 0;             // tip vertices (where a cut ends inside a face; 2 for an interior stroke)
  double bottom_w = 0.0;            // parameter w of the cut's bottom (the depth) on the lattice
  glm::ivec3 controls{0};           // (l, m, n) used, before knot insertion
  std::vector<std::uint8_t> moved;  // #V' : 1 where the vertex is new or its position changed, else 0
  // #V' × 3: every vertex of `mesh` with the opening left out (the cut made, nothing moved apart: input vertices at
  // their input positions, cut and wall vertices where opening 0 puts them) — the base of the opening's morph channel
  // (incision.animate: positions are closed + s·(mesh − closed)).
  std::vector<glm::dvec3> closed;
};
// Wall faces of a construction: wall_faces = 4 · wall_rows · split_faces when walls are on (each split face gives one
// rim edge per side; each rim edge gets a strip of wall_rows quads = 2·wall_rows triangles on its side).

// Cuts `surface` (world units; normals, uvs and face_material optional and kept) along `frame` (seed §6.4).
// Output order: the input vertices (same indices; those inside the lattice moved by the opening, the others bit for
// bit unchanged), then the new vertices in face order (per cut edge a minus and a plus vertex, per tip face its tip),
// then the wall vertices. Triangles: the input's,
// each split face replaced in place by its first piece, the other pieces appended, then the walls. face_material
// is filled when the input had one or walls were added. Vertices and faces away from the cut cost one pass each.
// Deterministic (the inversion runs in parallel, per vertex).
// Throws std::invalid_argument with a message starting with the parameter's name ("width: …"): width / depth ≤ 0 or
// non-finite, opening < 0 or so wide that the opened lattice folds over (seed Theorem 6), order outside 2..4,
// controls / wall_rows / eps out of range, a degenerate frame ("stroke: …"). A cut that crosses no face returns
// the surface unchanged (cut_edges = 0).
IncisionResult incise(const TriMesh& surface, const IncisionFrame& frame, const IncisionParams& params);

// The un-opened local lattice of Eq. 6.2 for `frame` (world units; no knots inserted yet), e.g. to draw it while
// dragging. Same parameter checks and errors as incise().
TrivariateBSpline<glm::dvec3> incision_lattice(const IncisionFrame& frame, const IncisionParams& params);

}  // namespace trispline::core
