// `camera.set` — sets the view used for rendering and for strokes that carry no camera of their own.
//   {"cmd":"camera.set","eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],"fov_deg":f,"viewport":[w,h]}
// eye/target world units; up need not be orthogonal to the view; fov_deg vertical, degrees; viewport pixels.
#pragma once

#include "core/commands/command.h"

namespace trispline::core {

class CameraSetCommand : public Command {
 public:
  explicit CameraSetCommand(const Camera& camera) : camera_(camera) {}
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  // Parses the camera fields of `j` (shared with place.sketch's optional "camera" object).
  static Camera parse_camera(const nlohmann::json& j);
  static nlohmann::json camera_json(const Camera& c);

  std::string id() const override { return "camera.set"; }
  nlohmann::json to_json() const override;
  std::string label() const override { return "Set camera"; }
  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  Camera camera_;
  Camera before_;
  bool before_set_ = false;
};

}  // namespace trispline::core
