#include "core/commands/volume_remove.h"

namespace trispline::core {

const ParamSchema<VolumeRemoveParams>& VolumeRemoveCommand::schema() {
  using P = VolumeRemoveParams;
  static const ParamSchema<P> s = ParamSchema<P>("volume.remove", "Remove a volume")
                                      .field("object", &P::object, {.required = true, .help = "A volume"});
  return s;
}

std::optional<VolumeObject> VolumeRemoveCommand::build(const Scene& scene) {
  require_volume(scene, p_.object);
  return std::nullopt;
}

}  // namespace trispline::core
