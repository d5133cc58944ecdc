#include "core/params/codecs.h"

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

const Camera& stroke_camera(const Scene& scene, const std::optional<Camera>& camera) {
  if (camera) return *camera;
  if (!scene.camera_set)
    throw CommandError(
        "field 'camera': stroke pixels need a camera: add a camera.set line before this one or a \"camera\" object "
        "to this line",
        "camera");
  return scene.camera;
}

const ParamSchema<Camera>& camera_schema() {
  using C = Camera;
  static const ParamSchema<Camera> schema =
      ParamSchema<C>("camera", "A pinhole camera")
          .field("eye", &C::eye, {.required = true, .unit = "world units", .help = "Position of the eye"})
          .field("target", &C::target,
                 {.required = true, .unit = "world units", .help = "Point looked at; differs from eye"})
          .check([](const C& c) {
            if (c.eye == c.target) params::fail("target", "eye and target coincide");
          })
          .field("up", &C::up, {.help = "Up direction; need not be orthogonal to the view, must not be parallel to it"})
          .check([](const C& c) {
            if (glm::length(glm::cross(glm::normalize(c.target - c.eye), c.up)) < 1e-9)
              params::fail("up", "up is parallel to the view direction");
          })
          .field("fov_deg", &C::fov_deg,
                 {.range = ParamRange{0, 180, true, true},
                  .unit = "degrees",
                  .ui = {"FOV"},
                  .help = "Vertical field of view"})
          .field("viewport", &C::viewport,
                 {.range = ParamRange::at_least(1), .unit = "pixels", .help = "Width and height of the image"});
  return schema;
}

glm::dvec3 ScaleCodec::read(const nlohmann::json& v, const std::string& field) {
  glm::dvec3 s;
  if (v.is_number()) {
    s = glm::dvec3(params::Codec<double>::read(v, field));
  } else if (v.is_array()) {
    s = params::Codec<glm::dvec3>::read(v, field);
  } else {
    params::fail(field, "expected a number or an array of 3 numbers, got " + std::string(v.type_name()));
  }
  if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) params::fail(field, "scale must be non-zero");
  return s;
}

nlohmann::json ScaleCodec::write(const glm::dvec3& s) {
  if (s.x == s.y && s.y == s.z) return s.x;
  return params::Codec<glm::dvec3>::write(s);
}

glm::dvec2 UniformVec2Codec::read(const nlohmann::json& v, const std::string& field) {
  if (v.is_number()) return glm::dvec2(params::Codec<double>::read(v, field));
  if (!v.is_array())
    params::fail(field, "expected a number or an array of 2 numbers, got " + std::string(v.type_name()));
  return params::Codec<glm::dvec2>::read(v, field);
}

const ParamSchema<Transform>& transform_schema() {
  using T = Transform;
  static const ParamSchema<T> s =
      ParamSchema<T>("transform", "Location, rotation and scale")
          .field("translate", &T::translate, {.unit = "world units", .help = "Location"})
          .field("rotate_deg", &T::rotate_deg,
                 {.unit = "degrees", .help = "Rotation about x, then y, then z (R = Rz·Ry·Rx)"})
          .field_as<ScaleCodec>("scale", &T::scale, {.help = "Scale per axis, applied first; non-zero"});
  return s;
}

const ParamSchema<ObjectFields>& object_fields_schema() {
  using O = ObjectFields;
  static const ParamSchema<O> s =
      ParamSchema<O>("object", "An added object's name, transform and colour")
          .field("name", &O::name,
                 {.default_text = "made unique from the source", .help = "Object id; an existing name is an error"})
          .check([](const O& o) {
            if (o.name.empty()) return;
            if (const std::string bad = object_name_error(o.name); !bad.empty()) params::fail("name", bad);
          })
          .embed(&O::transform, transform_schema())
          .field("color", &O::color, {.range = ParamRange{0, 1}, .default_text = "palette", .help = "Linear RGB"});
  return s;
}

}  // namespace trispline::core
