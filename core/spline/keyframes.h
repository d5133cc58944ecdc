// trispline::core keyframes — keyed values over scene time (Blender's keyframes with constant / linear / ease
// interpolation), shared by FFD parameter offsets (anim.keyframe) and DDM tile animation (ddm.animate).
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace trispline::core {

// How a keyed value moves from one key to the next (Blender's keyframe interpolation, set on the earlier key).
enum class KeyInterpolation { constant, linear, smooth };  // smooth = ease in/out (cubic with flat tangents)

// One keyframe of a keyed value: an object's parameter offset (anim.keyframe), a DDM layer's texture-space offset
// or metamorphosis α (ddm.animate; α in offset.x). Keys are kept sorted by time, one per time.
struct OffsetKey {
  double time_s = 0;       // scene time, seconds (anim.keyframe takes a frame and converts it)
  glm::dvec3 offset{0.0};  // parameter units, like SceneObject::param_offset
  KeyInterpolation interpolation = KeyInterpolation::linear;
};

// Value of sorted `keys` (non-empty) at `time_s`: held constant before the first and after the last key.
glm::dvec3 evaluate_offset_keys(const std::vector<OffsetKey>& keys, double time_s);

}  // namespace trispline::core
