#include "core/commands/scene_remove.h"

#include "core/commands/json_fields.h"

namespace trispline::core {

CommandPtr SceneRemoveCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<SceneRemoveCommand>();
  c->name_ = json_fields::get_string(j, "name");
  return c;
}

std::optional<SceneObject> SceneRemoveCommand::build(const Scene& scene) {
  if (scene.index_of(name_) < 0) throw CommandError("no object named '" + name_ + "'", "name");
  return std::nullopt;
}

}  // namespace trispline::core
