#include "core/commands/volume_iso.h"

#include <cstdio>

namespace trispline::core {

const ParamSchema<VolumeIsoParams>& VolumeIsoCommand::schema() {
  using P = VolumeIsoParams;
  static const ParamSchema<P> s = ParamSchema<P>("volume.iso", "Set a volume's iso-level (the surface D = level)")
                                      .field("object", &P::object)
                                      .required()
                                      .help("A volume")
                                      .field("level", &P::level)
                                      .required()
                                      .magnitude_at_most(1e30)
                                      .unit("volume units")
                                      .label("Iso-level")
                                      .help("Iso-level in the volume's units (HU for CT)");
  return s;
}

std::string VolumeIsoCommand::label() const {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", p_.level);
  return "Iso-level of '" + p_.object + "' " + buf;
}

std::optional<VolumeObject> VolumeIsoCommand::build(const Scene& scene) {
  VolumeObject v = require_volume(scene, p_.object);
  v.iso = p_.level;
  const bool in_range = p_.level >= v.table->range_min() && p_.level <= v.table->range_max();
  stats_["level"] = p_.level;
  stats_["in_range"] = in_range;
  stats_["cells"] = v.table->cells_holding(p_.level).size();
  return volume_with_silhouettes(v, scene.camera, &stats_);
}

}  // namespace trispline::core
