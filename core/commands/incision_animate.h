// `incision.animate` — an incision's opening keyed on the timeline (seed §6.4: the kernel κ opening after Eq. 6.2),
// through the object's per-vertex morph channel (SceneObject::morph, made by incision.draw): at opening s the surface
// is closed + s·(cut − closed) — s = 0 the cut closed (the two faces touching), s = 1 the opening incision.draw made.
// Fields: declared in incision_animate.cpp (ParamSchema, keyed_weight_schema in anim_keys.cpp), listed in
// docs/commands.md. The keys' frames are converted with the current timeline, like anim.keyframe's; s outside [0, 1]
// extrapolates (below 0 the faces pass through each other). One key holds that opening at every time.
// The object's world mesh is re-evaluated at scene time 0; scene_at_time evaluates it at any time (replay --time,
// anim.record, animation.glb), the editor plays it on the CPU. Tile layers on the object follow (ddm_follow.h).
// Errors beyond the declared ranges (CommandError, field named; the scene is unchanged): unknown object, an object
// without an incision's channel or with an FFD / DFFD ("object"); keys non-finite or |s| > 100, none, or two on one
// frame ("opening_keys").
// report.json: keys, opening_at_start.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/commands/anim_keys.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct IncisionAnimateCommand
    : ObjectSnapshotCommand<IncisionAnimateCommand, KeyedWeightParams> {  // keys: "opening_keys"
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
