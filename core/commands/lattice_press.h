// `lattice.press` — one drag of the pressing sphere on a placed object's control lattice = one command (seed §2.4.1,
// Fig. 2.7, 2.8). Fields: declared in lattice_press.cpp (ParamSchema), listed in docs/commands.md. The maths:
// a control point P_ijk moves by −s·w·V_P with w = max over the path's centres c of falloff(|P_ijk − c| / r)
// (falloff.h), so a control point is moved once by the strongest weight the swept sphere gave it — dragging over it
// twice in one stroke does not press twice, and points outside every sphere do not move; s > 0 presses down into the
// volume, s < 0 pulls up. V_P is the unit direction of the control point's column, from the contact control point
// P_ij0 to the top P_ij(n−1): the extrusion direction V for an extruded volume (F1), the contact surface's offset
// normal for F2 (seed Eq. 2.3, 2.4). Positions before the command decide the weights and directions. With
// keep_fold_free the strength is limited (bisection) so that the pressed lattice stays certified fold-free
// (core/ffd/fold_certificate.h); a lattice not certified before the press is refused (`keep_fold_free`).
// Errors beyond the declared ranges (CommandError, field named): unknown object / no lattice (`object`), a column of
// zero length (`object`). stats(): moved (control points moved), max_displacement (world units), ms_evaluate; with
// keep_fold_free also strength_used (world units), limited (bool), certificates, ms_certify.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/ffd/falloff.h"
#include "core/placement/pressing.h"

namespace trispline::core {

struct LatticePressParams {
  std::string object;
  std::vector<glm::dvec3> path;  // #P × 3 sphere centres, world units
  double radius = 0.1;           // world units
  double strength = 0.05;        // world units; < 0 pulls
  std::string falloff = "smooth";
  bool keep_fold_free = false;  // limit the strength so that the lattice stays certified fold-free
};

class LatticePressCommand : public ObjectSnapshotCommand<LatticePressCommand, LatticePressParams> {
 public:
  static Schema declare();

  // A negative strength pulls (the Press tool's Ctrl+drag); a press limited to stay fold-free says to what.
  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
