// `ddm.color` — a tile layer's own colour, or its object's again. Fields: declared in ddm_color.cpp (ParamSchema),
// listed in docs/commands.md.
// Tiles, maps and mesh stay shared with the previous state. Errors: unknown object ("object"), no such layer ("layer").
#pragma once

#include <optional>
#include <string>

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmColorParams {
  std::string object, layer;
  std::optional<glm::vec3> color;  // unset: "color": null (the object's colour again)
};

struct DdmColorCommand : ObjectSnapshotCommand<DdmColorCommand, DdmColorParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
