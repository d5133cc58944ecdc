// `ddm.color` — a tile layer's own colour, or its object's again:
//   {"cmd":"ddm.color","object":"ID","layer":"NAME","color":[r,g,b] | null}   (linear RGB in [0, 1])
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

class DdmColorCommand : public ObjectSnapshotCommand<DdmColorCommand, DdmColorParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<DdmColorParams>& schema();
  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

// {"cmd":"ddm.remove","object":ID,"layer":NAME}: deletes a tile layer (its tiles, maps and animation); undo brings it
// back as it was. Errors (field named, scene unchanged): unknown object, no such layer.

}  // namespace trispline::core
