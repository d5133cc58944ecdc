// `camera.set` — sets the view used for rendering and for strokes that carry no camera of their own.
// Fields: codecs.h camera_schema() (eye, target, up, fov_deg, viewport); docs/commands.md lists them.
#pragma once

#include "core/commands/declared_command.h"

namespace trispline::core {

class CameraSetCommand : public DeclaredCommand<CameraSetCommand, Camera> {
 public:
  static Schema declare();

  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  Camera before_;
  bool before_set_ = false;
};

}  // namespace trispline::core
