// `lattice.animate_offset` — moves a deformed object through its lattice's parameter domain (seed §4.5): the object
// shows F(E(x) + offset + velocity·t) at scene time t (seconds). On a periodic axis (lattice.ring) an offset of 1 is
// one period of the axis — one turn of a ring, two turns of a half-twisted band (twist_deg 180) — so the object
// travels around the ring forever; on other axes the parameters clamp at the domain's ends. Playback evaluates the
// moving offset in the vertex shader (glsl_vertex path); the object's geometry for export is the t = 0 pose
// (replay --time T exports the pose at T).
// Fields: declared in lattice_animate_offset.cpp (ParamSchema), listed in docs/commands.md.
// Errors beyond the declared ranges (CommandError, field named): unknown object, object without an FFD (`object`).
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct LatticeAnimateOffsetParams {
  std::string object;
  glm::dvec3 offset{0.0};    // parameter units
  glm::dvec3 velocity{0.0};  // parameter units per second
};

struct LatticeAnimateOffsetCommand : ObjectSnapshotCommand<LatticeAnimateOffsetCommand, LatticeAnimateOffsetParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
