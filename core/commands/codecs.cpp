#include "core/commands/codecs.h"

#include <algorithm>

namespace trispline::core {

const std::vector<std::string>& axis_names() {
  static const std::vector<std::string> names = {"x", "y", "z"};
  return names;
}

int axis_index(const std::string& name) { return name == "x" ? 0 : name == "y" ? 1 : 2; }

const char* axis_name(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return names[std::clamp(axis, 0, 2)];
}

const ParamSchema<Camera>& camera_schema() {
  using C = Camera;
  static const ParamSchema<Camera> schema =
      ParamSchema<C>("camera", "A pinhole camera")
          .field("eye", &C::eye).required().unit("world units").help("Position of the eye")
          .field("target", &C::target).required().unit("world units").help("Point looked at; differs from eye")
          .check([](const C& c) {
            if (c.eye == c.target) params::fail("target", "eye and target coincide");
          })
          .field("up", &C::up).help("Up direction; need not be orthogonal to the view, must not be parallel to it")
          .check([](const C& c) {
            if (glm::length(glm::cross(glm::normalize(c.target - c.eye), c.up)) < 1e-9)
              params::fail("up", "up is parallel to the view direction");
          })
          .field("fov_deg", &C::fov_deg).range(0, 180, true, true).unit("degrees").label("FOV")
          .help("Vertical field of view")
          .field("viewport", &C::viewport).at_least(1).unit("pixels").help("Width and height of the image");
  return schema;
}

}  // namespace trispline::core
