#include "core/commands/volume_remove.h"

namespace trispline::core {

auto VolumeRemoveCommand::declare() -> Schema {
  return Schema("volume.remove", "Remove a volume")
      .field("object", &P::object, {.required = true, .help = "A volume"})
      .label([](const P& p) { return "Remove volume '" + p.object + "'"; });
}

std::optional<VolumeObject> VolumeRemoveCommand::build(const Scene& scene) {
  require_volume(scene, p_.object);
  return std::nullopt;
}

}  // namespace trispline::core
