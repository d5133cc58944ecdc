// `ddm.remove` — deletes a tile layer. Fields: declared in ddm_remove.cpp (ParamSchema), listed in docs/commands.md.
// report.json: tiles, vertices (of the removed layer). Errors: unknown object ("object"), no such layer ("layer").
#pragma once

#include <optional>
#include <string>

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmRemoveParams {
  std::string object, layer;
};

struct DdmRemoveCommand : ObjectSnapshotCommand<DdmRemoveCommand, DdmRemoveParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
