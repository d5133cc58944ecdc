// `lattice.ring` — binds an object to a ring-shaped control lattice that is periodic along u, so the object can
// travel around the ring without a seam (seed §4.5, Fig. 4.5: whales swimming around a periodic deformation); with
// twist_deg the ring's cross-section turns about its centre line as it goes round, 180° making a Möbius band (Fig. 4.6:
// ants walking round one).
// Fields: declared in lattice_ring.cpp (ParamSchema), listed in docs/commands.md.
// The ring lies in the plane y = center.y around the vertical axis through `center`; u runs from +x towards +z
// (clockwise seen from +y), v outwards across the ring, w up (so det J > 0 and the object keeps its orientation).
// Knot vectors: u periodic uniform with controls[0] control points, v and w clamped uniform. One period of u (1 in
// parameter units) is laps = ring_twist_laps(twist_deg) turns: 1 untwisted, 2 for a half twist (the first turn on top
// of the band, the second upside down beneath it), 4 for a quarter twist. The object's length (its bounding box along
// length_axis) covers u ∈ [phase, phase + span]; the default span, length / (2π·radius·laps), keeps the object's
// proportions. Replaces any previous FFD of the object and resets its parameter offset and offset velocity. Undo
// restores the object as it was.
// Errors beyond the declared ranges (CommandError, field named): unknown object; radius ≤ width/2 (the inner edge
// would cross the axis), twisted and radius ≤ hypot(width/2, height) (the turning cross-section would), or an object
// longer than the ring's period (default span ≥ 1) ("radius"); twist_deg not a multiple of 90 ("twist_deg"); twisted
// with controls[0] not a multiple of the laps or fewer than 3 per turn ("controls").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/placement/ring_lattice.h"

namespace trispline::core {

struct LatticeRingParams {
  std::string object;
  glm::dvec3 center{0.0};
  double radius = 1.0;     // world units
  double width = 0.0;      // world units; 0 = the object's extent across the ring
  double height = 0.0;     // world units; 0 = the object's extent up
  double span = 0.0;       // fraction of the u period covered by the object; 0 = length / (2π·radius·laps)
  double phase = 0.0;      // u where the object starts, parameter units (one period = laps turns = 1)
  double twist_deg = 0.0;  // degrees per turn, a multiple of 90 in [−720, 720]; 180 = a Möbius band
  glm::ivec3 controls{16, 2, 2};
  glm::ivec3 order{4, 2, 2};
  std::string length_axis = "x";
  std::string up_axis = "y";
};

struct LatticeRingCommand : ObjectSnapshotCommand<LatticeRingCommand, LatticeRingParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
