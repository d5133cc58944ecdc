// `scene.remove` — removes an object. Fields: declared in scene_remove.cpp (ParamSchema), listed in docs/commands.md.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct SceneRemoveParams {
  std::string name;
};

class SceneRemoveCommand : public DeclaredCommand<SceneRemoveCommand, SceneRemoveParams, SnapshotCommand> {
 public:
  static Schema declare();

  std::string label() const override { return "Remove '" + p_.name + "'"; }

 protected:
  std::string target() const override { return p_.name; }
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
