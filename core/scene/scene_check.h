// trispline::core scene checks — what every command's result must satisfy before it is accepted.
//
// A command's numbers can be individually valid and still produce nonsense together (a scale of 1e308 times a
// vertex at 10 overflows; a lattice pulled 1e308 world units leaves every deformed vertex at infinity). Rather than
// every command guessing which of its inputs could overflow, the history checks the *result*: SceneGuard records
// what a scene holds before a command runs and, after it, reports the first value the command produced that is not
// finite or lies beyond kMaxWorldCoordinate (scene.glb stores float32: larger values lose all precision there, and
// beyond 3.4e38 become infinities). Unchanged meshes (same shared pointer) are not scanned again, so the check costs
// one pass over what the command actually built.
#pragma once

#include <map>
#include <set>
#include <string>

#include "core/scene/scene.h"

namespace trispline::core {

// Coordinates (world units) a scene may hold; 1e12 world units is far beyond any modelled scene and keeps float32
// export meaningful.
inline constexpr double kMaxWorldCoordinate = 1e12;

// "" when every position, normal, transform, lattice control point, offset, tile-layer vertex and the camera are
// finite and positions lie within ±kMaxWorldCoordinate; else the first offender ("object 'ball': vertex 12 of its
// mesh is not finite"). Objects and meshes in `unchanged` (by pointer) are skipped.
std::string scene_value_error(const Scene& scene, const std::set<const void*>& unchanged = {});

// Remembers the meshes and lattices of `scene` as they are now; error() checks only what changed since.
class SceneGuard {
 public:
  explicit SceneGuard(const Scene& scene);
  std::string error(const Scene& scene) const;  // scene_value_error(scene, what was there before)

 private:
  std::set<const void*> before_;
};

}  // namespace trispline::core
