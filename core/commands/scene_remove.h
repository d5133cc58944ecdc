// `scene.remove` — removes an object. Fields: declared in scene_remove.cpp (ParamSchema), listed in docs/commands.md.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct SceneRemoveParams {
  std::string name;
};

class SceneRemoveCommand : public DeclaredSnapshotCommand<SceneRemoveCommand, SceneRemoveParams, SnapshotCommand> {
 public:
  static Schema declare();

 protected:
  std::string target() const override { return p_.name; }
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
