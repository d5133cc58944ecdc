// `lattice.set_point` — moves one control point of a deformed object's FFD lattice to an exact position (the Tool
// panel's "Control point" section: precise, undoable edits of P_ijk; seed §2.4.1 edits the lattice by hand too).
// Fields: declared in lattice_set_point.cpp (ParamSchema), listed in docs/commands.md; the lattice lives in world
// space. The object is re-evaluated with the same embedding and parameters; undo restores the object bit for bit
// (SnapshotCommand).
// Errors beyond the declared ranges (CommandError, field named, scene untouched): unknown object / no lattice
// (`object`), index outside the lattice (`index`, names the counts).
// stats(): moved (1, or 0 when the point already was there), displacement (world units), ms_evaluate.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct LatticeSetPointParams {
  std::string object;
  glm::ivec3 index{0};       // (i, j, k) of the control point
  glm::dvec3 position{0.0};  // world units
};

struct LatticeSetPointCommand : ObjectSnapshotCommand<LatticeSetPointCommand, LatticeSetPointParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
