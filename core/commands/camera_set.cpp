#include "core/commands/camera_set.h"

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

Camera CameraSetCommand::parse_camera(const nlohmann::json& j) {
  Camera c;
  c.eye = jf::get_vec3(j, "eye");
  c.target = jf::get_vec3(j, "target");
  c.up = jf::get_vec3(j, "up", glm::dvec3(0, 1, 0));
  c.fov_deg = jf::get_number(j, "fov_deg", 45.0);
  if (jf::has(j, "viewport")) c.viewport = jf::get_ivec2(j, "viewport");
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const char* field = msg.find("fov") != std::string::npos        ? "fov_deg"
                        : msg.find("viewport") != std::string::npos ? "viewport"
                        : msg.find("up") != std::string::npos       ? "up"
                                                                    : "target";
    throw CommandError("field '" + std::string(field) + "': " + msg, field);
  }
  return c;
}

nlohmann::json CameraSetCommand::camera_json(const Camera& c) {
  return {{"eye", jf::to_json(c.eye)},
          {"target", jf::to_json(c.target)},
          {"up", jf::to_json(c.up)},
          {"fov_deg", c.fov_deg},
          {"viewport", jf::to_json(c.viewport)}};
}

CommandPtr CameraSetCommand::parse(const nlohmann::json& j, const CommandContext&) {
  return std::make_unique<CameraSetCommand>(parse_camera(j));
}

nlohmann::json CameraSetCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}};
  j.update(camera_json(camera_));
  return j;
}

void CameraSetCommand::redo(Scene& scene) {
  before_ = scene.camera;
  before_set_ = scene.camera_set;
  scene.camera = camera_;
  scene.camera_set = true;
}

void CameraSetCommand::undo(Scene& scene) {
  scene.camera = before_;
  scene.camera_set = before_set_;
}

}  // namespace trispline::core
