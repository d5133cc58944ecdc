// `volume.remove` — removes a volume (Scene panel ▸ Remove, the Delete key on a selected volume). Fields: declared in
// volume_remove.cpp (ParamSchema), listed in docs/commands.md.
// Undo puts it back where it was, with its iso-level, settings and silhouettes. Error (field `object`): no such volume.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

struct VolumeRemoveParams {
  std::string object;
};

struct VolumeRemoveCommand : ObjectSnapshotCommand<VolumeRemoveCommand, VolumeRemoveParams, VolumeSnapshotCommand> {
  static Schema declare();
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
