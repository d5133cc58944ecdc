// `dffd.animate` — a DFFD's seam keyed on the timeline between its capped openings and its stitched seam (seed §6.3.2,
// Fig. 6.3 / 6.7b: the openings an obstacle leaves behind it, and their stitching at the level w_s). At stitch weight
// s the lattice is (1 − s)·open + s·stitched (DffdSeam), so each vertex moves on the straight line between its capped
// and its stitched position: the per-vertex morph of one topology (the split and its caps do not change with s).
// Fields: declared in dffd_animate.cpp (ParamSchema, keyed_weight_schema in anim_keys.cpp), listed in
// docs/commands.md. The keys' frames are converted with the current timeline, like anim.keyframe's; s outside [0, 1]
// extrapolates. One key holds that state at every time.
// The object's world mesh is re-evaluated at scene time 0; scene_at_time evaluates it at any time (replay --time,
// anim.record, animation.glb), the editor plays it on the CPU with the walk (its u offset keys). Tile layers on the
// object follow (ddm_follow.h).
// Errors beyond the declared ranges (CommandError, field named; the scene is unchanged): unknown object, an object
// without a DFFD rig, a rig split with "openings":"open" (no caps: the stitched state has another topology)
// ("object"); keys non-finite or beyond ±100 (kMaxKeyedWeight), none, or two on one frame ("stitch_keys").
// report.json: keys, stitch_at_start.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/commands/anim_keys.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DffdAnimateCommand : ObjectSnapshotCommand<DffdAnimateCommand, KeyedWeightParams> {  // keys: "stitch_keys"
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
