// trispline::core iso-surface ray casting — the first crossing of D = c along a ray, on the spline itself (seed
// §7.3: the iso-surface of the trivariate D is rendered exactly, no mesh). The CPU double reference of the GLSL ray
// caster (gpu/eval/volume_gl.h, shaders/volume_iso.frag.glsl), which implements the same steps in float.
//
//   VolumeRangeGrid / build_volume_range_grid   coarse min/max bricks for empty-space skipping (CPU and GPU)
//   iso_ray_hit                                 one world ray → first crossing, index and world point, normal
//   pixel_ray / render_iso_hits_cpu             the ray of a viewport pixel; a small image of hits (tests)
//
// The march (the same on the GPU): the ray is mapped to index space, clipped to the grid box [0, nx−1] × [0, ny−1] ×
// [0, nz−1] (and to t ∈ [0, t_max]), and D − c is sampled at index-space arc lengths s_m = m·step from the entry point
// (m = 0, 1, …) and at the exit point. The first sample pair whose signs differ (zero counts as positive) brackets the
// crossing, refined by regula falsi with the Illinois modification (Dowell & Jarratt 1971) until the bracket is
// shorter than 1e-9 index units — the sign-change detection and iterative refinement of Hadwiger et al. 2005,
// "Real-time ray-casting and advanced shading of discrete isosurfaces". Crossings in either direction count (a ray
// starting inside the object hits where it leaves); two crossings within one step are not seen (the step bounds the
// thinnest feature found).
//
// With a VolumeRangeGrid the same samples decide, but most of their signs are known without evaluating D (empty-space
// skipping, Hadwiger et al. 2005 §4): the bricks are walked front to back (a 3D DDA); every sample in a brick whose
// range excludes c has the sign of that range (convex hull property) and is not evaluated; in the other bricks a
// sample with |D − c| = f is followed by ⌊f / (slope · |u|₁ · step)⌋ samples of the same sign (|dD/ds| ≤ slope ·
// |u|₁ on the brick, u the unit index-space direction), also not evaluated. Only the two samples of the bracket are
// needed as values, so the first sign change — and the hit, bit for bit — is the one of the plain march.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "core/volume/volume_spline.h"

namespace trispline::core {

// Value and slope bounds of D over bricks of `brick`³ index units: brick (a, b, c) covers the index-space box
// [brick·a, brick·(a+1)] × … clipped to the grid box (the last bricks may be shorter). range(a, b, c) = (min, max) of
// the control points that weigh D somewhere in the brick (the support of its knot spans: (brick + order − 1)³ controls
// inside the grid, fewer at its border), so D − c has one sign in a brick whose range excludes c (convex hull property
// of B-splines). slope(a, b, c) bounds |∂D/∂x|, |∂D/∂y| and |∂D/∂z| on the brick (per index unit): the largest
// difference of two neighbouring control points of that support and the next one along an axis (∂D/∂x is a B-spline
// of order k − 1 over the differences P_{i+1} − P_i).
struct VolumeRangeGrid {
  int brick = 4;                     // index units per brick axis
  std::array<int, 3> dims{0, 0, 0};  // bricks per axis: ceil((n − 1) / brick), at least 1
  std::vector<glm::vec2> range;      // dims[0]·dims[1]·dims[2] (min, max), x fastest, in the volume's units
  std::vector<float> slope;          // dims[0]·dims[1]·dims[2], the volume's units per index unit, ≥ 0

  std::size_t index(int a, int b, int c) const {
    return static_cast<std::size_t>(a) +
           static_cast<std::size_t>(dims[0]) * (static_cast<std::size_t>(b) + static_cast<std::size_t>(dims[1]) * c);
  }
  glm::vec2 at(int a, int b, int c) const { return range[index(a, b, c)]; }
  // The brick holding index-space point x (clamped to the grid of bricks).
  std::array<int, 3> brick_of(const glm::dvec3& x) const;
};

// Builds the grid in O(#controls) (separable sliding min / max). Throws std::invalid_argument when brick < 1.
VolumeRangeGrid build_volume_range_grid(const VolumeSpline& spline, int brick = 4);

// A world ray in the spline's index space, clipped to the grid box [0, n−1]³ and to t ∈ [0, t_max]: the march's
// start and length (index units), `u` the unit index-space direction and `index_per_t` the index length of one unit
// of t. inside is false when the ray misses the box (the other fields are then unset). Throws std::invalid_argument
// ("<caller>: zero ray direction") for a zero or non-finite direction (the caller checks the origin). Shared by
// iso_ray_hit and dvr_ray.
struct GridRay {
  bool inside = false;
  glm::dvec3 entry{0.0}, u{0.0};
  double length = 0.0, index_per_t = 0.0;
  double s_entry = 0.0;  // index arc length from the origin to `entry`
};
GridRay clip_ray_to_grid(const VolumeSpline& spline, const glm::dvec3& world_origin, const glm::dvec3& world_dir,
                         double t_max, const char* caller);

// The first crossing along a ray. When hit is false the other fields are zero.
struct IsoHit {
  bool hit = false;
  double t = 0.0;                // ray parameter: world_point = world_origin + t · world_dir (t ≥ 0)
  glm::dvec3 index_point{0.0};   // index space
  glm::dvec3 world_point{0.0};   // millimetres
  glm::dvec3 world_normal{0.0};  // unit, −∇D / |∇D| in world space: points to where D decreases (out of the
                                 // region D > c, e.g. out of bone in CT); zero where ∇D = 0
};

// First crossing of D = iso along world_origin + t · world_dir, t ∈ [0, t_max], inside the grid box (see the header
// comment for the march). world_origin, world_dir: millimetres (world_dir need not be unit); step_index: march step,
// index units (0.25 = four samples per voxel); bricks: optional empty-space skipping (built from this spline; the
// result is the same without it). Throws std::invalid_argument: non-finite origin / direction, zero direction,
// step_index not finite or ≤ 0, t_max NaN or < 0, bricks of another grid size.
IsoHit iso_ray_hit(const VolumeSpline& spline, double iso, const glm::dvec3& world_origin, const glm::dvec3& world_dir,
                   double step_index = 0.25, double t_max = std::numeric_limits<double>::infinity(),
                   const VolumeRangeGrid* bricks = nullptr);

// The ray of viewport pixel (x, y) — GL window coordinates, y up from the bottom row, pixel centre at (x + ½, y + ½) —
// for a camera given by `view` and `projection` (OpenGL clip space, depth −1…1; perspective or orthographic) and
// `viewport` (x, y, width, height in pixels): origin on the near plane (world), direction towards the point at NDC
// depth 0 (world, not unit). The GLSL ray caster builds its rays the same way.
struct PixelRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0};
};
PixelRay pixel_ray(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport, int x, int y);

// iso_ray_hit for every pixel of a width × height viewport at (0, 0): hits[x + width·y], y up from the bottom row (the
// order glReadPixels returns). A hit whose window depth would lie beyond the far plane is dropped. Throws as
// iso_ray_hit, and std::invalid_argument for a non-positive size. Single-threaded: meant for small test images.
struct IsoHitImage {
  int width = 0, height = 0;
  std::vector<IsoHit> hits;   // width·height, bottom row first
  std::vector<double> depth;  // width·height window depth in [0, 1] (default depth range), 1 for misses
};
IsoHitImage render_iso_hits_cpu(const VolumeSpline& spline, double iso, const glm::dmat4& view,
                                const glm::dmat4& projection, int width, int height, double step_index = 0.25,
                                const VolumeRangeGrid* bricks = nullptr);

}  // namespace trispline::core
