// `dffd.cut` — one C⁻¹ discontinuity in a deformed object's lattice, its mesh split there and the cut opened
// (seed §6.3.1 Def. 6 and §6.3.2, the "left open" case; the building block of dffd.split and incision.draw).
// Fields: declared in dffd_cut.cpp (ParamSchema), listed in docs/commands.md.
// Inserts `order` knots at u0 = at (strictly inside the parameter domain, not already a break) on the lattice axis
// (core::insert_discontinuity), splits every edge and face of the embedded mesh that crosses u0 exactly
// (core::split_mesh_at_parameter: cut vertices interpolate position, normal and uv and move to u0 ∓ eps), then opens
// the cut by moving the F⁻ plane by −g/2 and the F⁺ plane by +g/2 (g = gap) along the lattice's mean direction
// of `axis` at the cut (centroid of the plane after F⁺ minus that of the plane before F⁻). g = 0 leaves the surface
// closed in space but split in topology. The openings stay open (the inside shows); kernel propagation, stitching
// and capping are dffd.split's (dffd_split.h). Undo restores the object (mesh, lattice, parameters) bit for bit.
// report.json: cut_edges, vertices_before, vertices_after, duplicated_on_plane, ms.
// Errors beyond the declared ranges (CommandError, field named): unknown object / no lattice / a glTF clip on it
// ("object"); u0 outside the domain or already a discontinuity, or a periodic axis ("at").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DffdCutParams {
  std::string object;
  int axis = 0;       // lattice axis: 0 u, 1 v, 2 w
  double at = 0.5;    // parameter of the cut
  double gap = 0.0;   // world units the two sides open by
  double eps = 1e-6;  // parameter units: cut vertices at at ∓ eps
};

struct DffdCutCommand : ObjectSnapshotCommand<DffdCutCommand, DffdCutParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
