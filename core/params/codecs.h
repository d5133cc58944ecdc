// Parameter declarations shared by several commands: axes, the camera a stroke was drawn in, object transforms.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/params/params.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"

namespace trispline::core {

// "x" | "y" | "z" ↔ 0 | 1 | 2.
const std::vector<std::string>& axis_names();
int axis_index(const std::string& name);  // "x" → 0; anything else than "x"/"y" → 2
const char* axis_name(int axis);          // 0 → "x"; clamped to [0, 2]

// {eye, target, up, fov_deg, viewport}: camera.set's fields, and the "camera" object of stroke commands. Checks
// what Camera::validate() checks, each error naming its field.
const ParamSchema<Camera>& camera_schema();

// The camera a stroke command's pixels were drawn in: the line's own `camera` object, else the scene's last
// camera.set. Throws CommandError (field 'camera') when there is neither.
const Camera& stroke_camera(const Scene& scene, const std::optional<Camera>& camera);

// "scale": a number s (uniform) or [sx,sy,sz], each non-zero; written as one number when uniform.
struct ScaleCodec {
  static constexpr ParamKind kind = ParamKind::Vec3;
  static glm::dvec3 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::dvec3& s);
  static std::string type() { return "number or [x,y,z]"; }
};

// A number a (read as [a, a]) or [x, y]; written as [x, y] (a tile's scale and shift in its cell).
struct UniformVec2Codec {
  static constexpr ParamKind kind = ParamKind::Other;
  static glm::dvec2 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::dvec2& x) { return params::Codec<glm::dvec2>::write(x); }
  static std::string type() { return "number or [x,y]"; }
};

// translate, rotate_deg, scale of an added object (every field written back).
const ParamSchema<Transform>& transform_schema();

// The fields every command that adds an object has: name (empty = made from the source by the command), the
// transform and the colour.
struct ObjectFields {
  std::string name;
  Transform transform;
  std::optional<glm::dvec3> color;  // linear RGB in [0,1]; unset = the palette's
};
const ParamSchema<ObjectFields>& object_fields_schema();

}  // namespace trispline::core
