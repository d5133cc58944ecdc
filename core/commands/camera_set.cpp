#include "core/commands/camera_set.h"

#include "core/params/codecs.h"

namespace trispline::core {

auto CameraSetCommand::declare() -> Schema {
  return Schema("camera.set", "Set the view (eye, target, up, field of view, viewport)")
      .include(camera_schema())
      .label([](const P& p) { return "Set camera"; });
}

void CameraSetCommand::redo(Scene& scene) {
  before_ = scene.camera;
  before_set_ = scene.camera_set;
  scene.camera = p_;
  scene.camera_set = true;
}

void CameraSetCommand::undo(Scene& scene) {
  scene.camera = before_;
  scene.camera_set = before_set_;
}

}  // namespace trispline::core
