// `lattice.ring` — binds an object to a ring-shaped control lattice that is periodic along u, so the object can
// travel around the ring without a seam (seed §4.5, Fig. 4.5: whales swimming around a periodic deformation).
// Fields: declared in lattice_ring.cpp (ParamSchema), listed in docs/commands.md.
// The ring lies in the plane y = center.y around the vertical axis through `center`; u runs from +x towards +z
// (clockwise seen from +y), v outwards across the ring, w up (so det J > 0 and the object keeps its orientation).
// The object's length (its bounding box along length_axis) covers u ∈ [phase, phase + span]; the default span,
// length / (2π·radius), keeps the object's proportions. Knot vectors: u periodic uniform with controls[0] control
// points (one period = one turn), v and w clamped uniform. Replaces any previous FFD of the object and resets its
// parameter offset and offset velocity. Undo restores the object as it was.
// Errors beyond the declared ranges (CommandError, field named): unknown object; radius ≤ width/2 (the inner edge
// would cross the axis) or an object longer than the ring (default span ≥ 1) ("radius").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/placement/ring_lattice.h"

namespace trispline::core {

struct LatticeRingParams {
  std::string object;
  glm::dvec3 center{0.0};
  double radius = 1.0;  // world units
  double width = 0.0;   // world units; 0 = the object's extent across the ring
  double height = 0.0;  // world units; 0 = the object's extent up
  double span = 0.0;    // fraction of the turn covered by the object; 0 = length / (2π·radius)
  double phase = 0.0;   // u where the object starts, parameter units (one turn = 1)
  glm::ivec3 controls{16, 2, 2};
  glm::ivec3 order{4, 2, 2};
  std::string length_axis = "x";
  std::string up_axis = "y";
};

class LatticeRingCommand : public ObjectSnapshotCommand<LatticeRingCommand, LatticeRingParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<LatticeRingParams>& schema();

  std::string label() const override { return "Ring lattice for '" + p_.object + "'"; }

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
