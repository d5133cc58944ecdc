#include "core/commands/volume_remove.h"

namespace trispline::core {

ParamSchema<VolumeRemoveParams> VolumeRemoveCommand::declare() {
  using P = VolumeRemoveParams;
  return ParamSchema<P>("volume.remove", "Remove a volume")
      .field("object", &P::object, {.required = true, .help = "A volume"});
}

std::optional<VolumeObject> VolumeRemoveCommand::build(const Scene& scene) {
  require_volume(scene, p_.object);
  return std::nullopt;
}

}  // namespace trispline::core
