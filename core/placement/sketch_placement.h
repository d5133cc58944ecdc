// trispline::core sketch placement — deform an object to lie along a stroke sketched over the scene
// (seed §2.3.1, Eq. 2.1–2.4, Fig. 2.3–2.5). The effect behind the `place.sketch` command.
//
// Index
//   PlacementVolume, SketchPlacementParams   input (pixels for the stroke, world units for width/height)
//   PlacementStats, SketchPlacementResult    output (FFD binding, placement record, statistics)
//   PlacementError                           what every bad input throws (names the field at fault)
//   place_along_stroke                       the whole pipeline in one call
//
// Pipeline (each step timed in PlacementStats):
//  fit      The stroke (#S viewport pixels) is resampled by arc length (one point per ~2 px, 8..256 points) and a
//           planar B-spline C(u) is least-squares fitted to it (chord-length parameters, fit_curve): order =
//           min(4, #distinct stroke points), controls = order + round(total turning angle / 60°), at most 16.
//  rays     Width in pixels: rays through the stroke samples give the scene depth under the stroke (median view
//           depth of the hits; the camera target's depth if none hit); pixels per world unit at that depth =
//           viewport_h / (2·depth·tan(fov/2)), d_px = d·that. Offsets C±(u) = C(u) ± d_px·N(u) (seed Eq. 2.2) with N
//           the unit image-plane normal, N = (T.y, −T.x) in pixel coordinates (y down), which puts C+ on the
//           viewer's left of the stroke so that ∂S/∂u × ∂S/∂v faces the camera (det J > 0, see `volume`).
//           Ruled surface R(u,v) = v·C+ + (1−v)·C−, sampled at nu samples uniform in the ARC LENGTH of C × nv samples
//           v_j = j/(nv−1); one ray per sample from Camera::eye through Camera::ray_direction; first hits recorded.
//  fill     Rays that miss get a point on their own ray at an interpolated view depth: in passes, every missing
//           sample with known 4-neighbours (in the nu×nv grid) takes the mean of their view depths (depth along
//           Camera::forward); all samples found in one pass are committed together (order-independent,
//           deterministic); passes repeat until the grid is full (fill_missing_depths, contact_grid.h). Filled
//           samples have contact_hit = 0 and lie on their own rays.
//           Threshold: the placement fails (PlacementError, field "stroke") when fewer than 50% of the rays hit —
//           the contact surface would then be mostly invented. Fewer misses (e.g. a stroke running off the edge of
//           an object) are bridged by the fill; the object then spans the gap at interpolated depth.
//  surface  The contact surface S(u,v) = F(u,v,0) is re-fitted through the nu×nv grid (fit_surface, clamped
//           knots from KnotVector::clamped_for_fit): v parameters = arc length along each cross-section (row i
//           fixed), averaged over the rows; u parameters = chord length along the middle column (seed §2.3.1).
//  volume   Lattice P_ijk (l×m×n = controls) with S's knot vectors in u and v and clamped uniform knots in w:
//             Extrude (F1, seed Eq. 2.3): P_ijk = P_ij0 + h·ξ_k·V, V = −Camera::forward() (toward the viewer: "up"
//                     for a top-down view; the seed leaves V free);
//             Offset  (F2, seed Eq. 2.4): P_ijk = P_ij0 + h·ξ_k·n_ij, n_ij = unit normal ∂S/∂u × ∂S/∂v of S at the
//                     Greville abscissae (ξ_i, ξ_j) (faces the camera by the choice of N; V where degenerate).
//           ξ_k are the Greville abscissae of the w knots (= k/(n−1) for order 2, the seed's k/(l−1)); with them F1 is
//           exactly S(u,v) + w·h·V (linear precision) for any order in w.
//  embed    The object's world rest positions are embedded with embed_bounding_box(axes): bounding box → [0,1]³,
//           length axis → u (along the stroke), up axis → w (bottom of the box at w = 0 → on S).
//  evaluate ffd_evaluate of the embedded positions → deformed positions (world units).
// The whole pipeline is sequential except ray casting and FFD evaluation, which are deterministic: two calls with
// the same inputs give bit-identical results.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ffd/ffd.h"
#include "core/placement/contact_springs.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"

namespace trispline::core {

enum class PlacementVolume { Extrude, Offset };  // seed Eq. 2.3 (F1) / Eq. 2.4 (F2)

struct SketchPlacementParams {
  std::vector<glm::dvec2> stroke_px;  // #S × 2 viewport pixels, (0,0) top-left, in drawing order (S ≥ 2)
  Camera camera;                      // the camera the stroke was drawn with
  double half_width = 0.25;           // d, world units (> 0): offsets at ±d from the stroke, converted at its depth
  double height = 0.25;               // h, world units (> 0): extent of the volume in w
  // Variable width and height (seed §2.4.1, Eq. 2.5): scaling functions of d and h, piecewise linear through samples
  // taken uniformly over the stroke's parameter u ∈ [0,1]. Empty = constant 1.
  //   width_profile   #K factors (K ≥ 2, each finite and > 0): the offsets are C(u) ± d·width(u)·N(u)
  //   height_profile  #R rows × #K factors (R ≥ 1 rows over v ∈ [0,1], K ≥ 2 over u, each > 0): the column over the
  //                   contact control point at Greville abscissae (ξ_i, ξ_j) gets height h·height(ξ_i, ξ_j) —
  //                   one row is h(u), several rows h(u,v) (bilinear).
  std::vector<double> width_profile;
  std::vector<std::vector<double>> height_profile;
  // Mass-spring relaxation of the contact surface's control points before the volume is built (seed §2.3.2,
  // contact_springs.h): each control point moves only along its column direction V_P (V for F1, the normal for F2)
  // and never below the scene under it, so the surface bridges gaps instead of sagging into them. Unset = off.
  std::optional<SpringParams> springs;
  int samples_u = 32;  // nu in [max(2, controls[0]), 4096]: contact samples along the stroke
  int samples_v = 8;   // nv in [max(2, controls[1]), 4096]: contact samples across the stroke
  PlacementVolume volume = PlacementVolume::Extrude;
  std::array<int, 3> order{4, 4, 2};     // per axis (u, v, w), = degree + 1, in [2, min(8, controls)]
  std::array<int, 3> controls{8, 4, 2};  // lattice control counts per axis (l, m, n), each in [2, 256]
  EmbeddingAxes axes;                    // object's length axis → u, up axis → w
  bool evaluate_positions = true;        // false: leave SketchPlacementResult::positions empty (the caller evaluates,
                                         // e.g. SceneObject::refresh with normals) instead of evaluating twice
};

struct PlacementStats {
  int rays_total = 0;                                 // nu·nv contact rays
  int rays_hit = 0;                                   // of which hit the scene
  int rays_filled = 0;                                // = rays_total − rays_hit (filled from neighbours)
  int stroke_rays = 0, stroke_rays_hit = 0;           // depth probes along the stroke
  double stroke_depth = 0;                            // view depth under the stroke, world units
  double pixels_per_world = 0;                        // at stroke_depth
  double half_width_px = 0;                           // d in pixels
  int curve_order = 0, curve_controls = 0;            // of C(u)
  double curve_fit_rms_px = 0, curve_fit_max_px = 0;  // residual of C at the resampled stroke, pixels
  double surface_fit_rms = 0, surface_fit_max = 0;    // residual of S at the contact grid, world units
  double min_det_jacobian = 0;  // min det J_F over a 5×5×3 grid of (u,v,w) in [0,1]³ (> 0: orientation kept)
  double ms_fit = 0, ms_rays = 0, ms_surface = 0, ms_springs = 0, ms_volume = 0, ms_embed = 0, ms_evaluate = 0;
  SpringStats springs;  // steps = 0 when the relaxation is off
};

struct SketchPlacementResult {
  FfdBinding binding;                 // lattice + embedding + per-vertex params: assign to SceneObject::ffd
  PlacementRecord record;             // stroke, contact grid and hit mask (for display / report)
  std::vector<glm::dvec3> positions;  // #V × 3 deformed positions, world units (same order as the input)
  PlacementStats stats;
};

// Thrown for every invalid input or failed placement. field() names the parameter at fault: "stroke", "camera",
// "width", "height", "width_profile", "height_profile", "samples", "order", "controls", "axes", "object".
class PlacementError : public std::runtime_error {
 public:
  PlacementError(std::string field, const std::string& message)
      : std::runtime_error("place.sketch: " + field + ": " + message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// Places the object whose world rest positions are `object_world_rest_positions` (#V × 3, world units, V ≥ 1)
// along params.stroke_px over the scene in `scene_rays` (committed; it must not contain the object itself).
// Throws PlacementError for: stroke with < 2 points, zero length or non-finite points ("stroke"); an invalid camera
// ("camera"); half_width or height ≤ 0 or non-finite ("width", "height"); samples < 2 or < controls in that axis
// ("samples"); order outside [2, min(8, controls)], controls outside [2, 256] ("order", "controls"); bad axes ("axes");
// empty or non-finite positions ("object"); no ray hitting, or fewer than 50% ("stroke", with counts).
SketchPlacementResult place_along_stroke(const RayCaster& scene_rays, const SketchPlacementParams& params,
                                         const std::vector<glm::dvec3>& object_world_rest_positions);

}  // namespace trispline::core
