#include "core/commands/scene_remove.h"

namespace trispline::core {

auto SceneRemoveCommand::declare() -> Schema {
  return Schema("scene.remove", "Remove an object")
      .field("name", &P::name, {.required = true, .help = "Id of the object to remove"})
      .label([](const P& p) { return "Remove '" + p.name + "'"; });
}

std::optional<SceneObject> SceneRemoveCommand::build(const Scene& scene) {
  if (scene.index_of(p_.name) < 0) throw CommandError("no object named '" + p_.name + "'", "name");
  return std::nullopt;
}

}  // namespace trispline::core
