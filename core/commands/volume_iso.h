// `volume.iso` — sets the iso-level c of a volume's surface D = c (seed Eq. 7.1). Fields: declared in volume_iso.cpp
// (ParamSchema), listed in docs/commands.md. A level outside the values D takes is allowed (nothing is shown) and
// reported (stats in_range = false). When the volume's silhouettes are enabled they are extracted again for the
// scene camera (the singleton table is reused: no new preprocessing). stats(): level, in_range, cells (singletons
// holding the level), and the silhouette figures when enabled.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

struct VolumeIsoParams {
  std::string object;
  double level = 0.0;
};

class VolumeIsoCommand : public DeclaredCommand<VolumeIsoCommand, VolumeIsoParams, VolumeSnapshotCommand> {
 public:
  using DeclaredCommand::DeclaredCommand;
  static const ParamSchema<VolumeIsoParams>& schema();
  std::string label() const override;

 protected:
  std::string target() const override { return p_.object; }
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
