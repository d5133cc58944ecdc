// `lattice.pull_column` — a pulling tool on a placed object's control lattice (seed §2.4.1): pulls (d > 0) or pushes
// (d < 0) a contact control point P_ij0 along V_P by d = distance and moves its whole column with it by the same
// vector. Fields: declared in lattice_pull_column.cpp (ParamSchema), listed in docs/commands.md.
// Errors beyond the declared ranges (CommandError, field named): unknown object / no lattice / a column of zero length
// (`object`), column outside the lattice (`column`). stats(): moved, max_displacement (world units), ms_evaluate.
#pragma once

#include <optional>
#include <string>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct LatticePullColumnParams {
  std::string object;
  glm::ivec2 column{0, 0};  // (i, j) of the contact control point
  double distance = 0.0;    // world units along V_P
};

struct LatticePullColumnCommand : ObjectSnapshotCommand<LatticePullColumnCommand, LatticePullColumnParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
