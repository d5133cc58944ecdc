// trispline::gpu — which instances of a live DDM layer the editor's interactive view draws (CPU, no GL; tested
// against the CPU reference mesh):
//   DdmInstanceBounds   per instance: a sphere enclosing its vertices and its root normal
//   ddm_lod_rank        per instance: its place in the motion LOD's order
//   DdmCullView         the view a frame is drawn in and what to leave out
//   ddm_instance_kept   the per-instance test: the view frustum, facing away, the motion LOD's share; the level of
//                       detail by size on screen
// Frustum culling is exact up to the sphere (an instance with a vertex inside the view is never left out); the
// back-facing test is a conservative cone on the base normal at the cell centre (docs/decisions.md: the margin);
// the motion LOD keeps the instances whose fixed pseudo-random rank is below a power-of-two share, so a thinned view
// is well spread and does not flicker while it orbits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/ddm/ddm_layer.h"

namespace trispline::gpu {

struct DdmInstanceBounds {
  std::vector<glm::vec4> spheres;  // #I: centre (xyz) and radius (w), object units, enclosing the instance's vertices
  std::vector<glm::vec3> normals;  // #I: unit base normal S's n at the cell centre (the root normal), object space
  glm::dvec3 lo{0.0}, hi{0.0};     // the box around every sphere, object units
  bool empty() const { return spheres.empty(); }
};

// The motion LOD's order: a fixed hash of the instance index in [0, 1); a thinned view draws the instances whose rank
// is below its share, so the same instances stay while the view moves and they spread over the whole layer.
float ddm_lod_rank(std::size_t instance);

// The bounds of `layer`'s instances at its time-0 pose, from its CPU reference mesh (layer.mesh: instances one after
// another in their tiles' vertex order); the spheres are widened by 1e-4 of the layer's extent (the GPU evaluates in
// float: docs/decisions.md holds it to 1e-5). Empty when the layer cannot be bounded this way: no mesh or maps, a
// mesh of another vertex count, or an animated layer (its instances move with time).
DdmInstanceBounds ddm_instance_bounds(const core::DdmLayer& layer);

// The view of one frame and what to leave out.
struct DdmCullView {
  glm::dmat4 view_proj{1.0};  // world → clip (OpenGL, depth in [-1, 1])
  glm::dmat4 model{1.0};      // object → world (Transform::matrix())
  glm::dvec3 eye{0.0};        // world units
  bool frustum = true;        // leave out instances wholly outside the view frustum
  // ≥ 0: leave out instances whose root normal faces away from the eye by more than 90° + this many degrees, seen from
  // anywhere in their sphere — the base is taken to hide them, as it does seen from outside; so never with the eye
  // inside the layer's box (from inside a pot the outside tiles show over its rim). < 0: no back-facing test.
  double backface_margin_deg = -1.0;
  double keep = 1.0;  // the motion LOD's share in (0, 1]: instances whose ddm_lod_rank ≥ keep are left out
  // Screen-size LOD: pixels one world unit spans at clip w = 1 (projection[1][1] × viewport height ÷ 2); 0 = off
  // (every kept instance at level 0).
  double pixels_per_unit = 0.0;
};

// The screen-size LOD's thresholds: an instance whose sphere is at least kDdmLodPixels[k] pixels across is drawn at
// level k or finer (gpu/eval/ddm_gl.h: level k has about 1/4^k of the tile's vertices); smaller ones at the coarsest.
inline constexpr double kDdmLodPixels[2] = {64.0, 16.0};

// The six planes of `view_proj` (left, right, bottom, top, near, far) as (n, d) with unit n pointing inside: a point
// x is inside when dot(n, x) + d ≥ 0 for all six (Gribb & Hartmann).
std::array<glm::dvec4, 6> frustum_planes(const glm::dmat4& view_proj);

// Why ddm_instance_kept leaves an instance out (kept = 0).
enum class DdmCullReason : std::uint8_t { kept = 0, outside, facing_away, thinned };

// Culls and thins a layer's instances (of `bounds`) for `view`, instance by instance; the reasons are tested in the
// order frustum, facing away, thinned. Precomputes the world planes and the model's
// scale once; cheap per instance (a matrix product and seven dot products).
class DdmCuller {
 public:
  DdmCuller(const DdmInstanceBounds& bounds, const DdmCullView& view);
  DdmCullReason test(std::size_t instance) const;  // instance < bounds.spheres.size()
  // The level of detail of a kept instance: 0 without pixels_per_unit, else by its sphere's size on screen
  // (kDdmLodPixels); 0 for a sphere whose centre is behind the eye.
  int level(std::size_t instance) const;

 private:
  const DdmInstanceBounds& bounds_;
  DdmCullView view_;
  std::array<glm::dvec4, 6> planes_;
  glm::dmat3 normal_matrix_;
  double scale_ = 1.0;    // largest axis scale of the model: object radius → world radius
  double margin_ = -1.0;  // backface_margin_deg in radians; < 0: no back-facing test
};

}  // namespace trispline::gpu
