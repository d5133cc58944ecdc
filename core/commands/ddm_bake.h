// `ddm.bake` — a layer as an ordinary mesh object (for export and for use elsewhere). Fields: declared in
// ddm_bake.cpp (ParamSchema), listed in docs/commands.md.
// The new object's mesh is the layer's (its animation at `frame`, else at scene time 0) in world units (the object's
// transform applied), identity transform, the object's colour; instances one after another, each in the tile's own
// vertex order. scene.glb then holds it. report.json: vertices, triangles.
// Errors beyond the declared ranges (CommandError, field named; the scene is unchanged): unknown object ("object"),
// no such layer ("layer"), name empty or taken ("name").
#pragma once

#include <optional>
#include <string>

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmBakeParams {
  std::string object, layer;
  std::string name;             // the new object
  std::optional<double> frame;  // timeline frame of the layer's animation; unset = scene time 0
};

class DdmBakeCommand : public DeclaredSnapshotCommand<DdmBakeCommand, DdmBakeParams, SnapshotCommand> {
 public:
  static Schema declare();
  bool preparable() const override { return true; }  // the editor bakes on a worker thread

 protected:
  std::string target() const override { return p_.name; }
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
