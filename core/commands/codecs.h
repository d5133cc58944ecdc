// Parameter declarations shared by several commands: axes, the camera a stroke was drawn in, object transforms.
#pragma once

#include <string>
#include <vector>

#include "core/commands/params.h"
#include "core/scene/camera.h"

namespace trispline::core {

// "x" | "y" | "z" ↔ 0 | 1 | 2.
const std::vector<std::string>& axis_names();
int axis_index(const std::string& name);  // "x" → 0; anything else than "x"/"y" → 2
const char* axis_name(int axis);          // 0 → "x"; clamped to [0, 2]

// {eye, target, up, fov_deg, viewport}: camera.set's fields, and the "camera" object of stroke commands. Checks
// what Camera::validate() checks, each error naming its field.
const ParamSchema<Camera>& camera_schema();

}  // namespace trispline::core
