// `volume.render` — how a volume is drawn (seed §7.4): its iso-surface D = iso ray cast on the spline ("iso", the
// default), or direct volume rendering of D through a 1-D transfer function ("dvr", Fig. 7.7; core/volume/volume_dvr.h:
// emission–absorption, colour and opacity per index unit linear between the function's points). Fields: declared in
// volume_render.cpp (ParamSchema), listed in docs/commands.md. "transfer" is [[value, r, g, b, a], …]: values in the
// volume's units (HU for CT) strictly increasing, 2–16 points, linear RGB and opacity in [0, 1]; left out, the volume
// keeps its own, and a volume switched to dvr without one gets a default: the CT preset for a volume in HU, else a
// ramp from the iso-level (transparent) to the volume's largest value (white, opacity 0.6). "step" is not kept: a
// line without it sets 0.5. The mode, transfer and step are saved with the scene and drawn by the editor, replay's
// renderer and recordings alike. stats(): mode, points (of the transfer function), step, visible_range ([lo, hi] of the
// values with opacity > 0). Errors beyond the declared ranges (CommandError, field named): a transfer point that is not
// [value, r, g, b, a] of finite numbers, and what transfer_function_error refuses ("transfer").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"
#include "core/volume/volume_dvr.h"

namespace trispline::core {

struct VolumeRenderParams {
  std::string object;
  VolumeObject::RenderMode mode = VolumeObject::RenderMode::iso;
  std::optional<TransferFunction> transfer;  // unset = kept (or the default, see the header)
  double step = 0.5;                         // dvr's segment length, index units
};

// The transfer function a volume switched to dvr without one gets (see the header comment).
TransferFunction default_transfer_function(const VolumeObject& volume);

struct VolumeRenderCommand : ObjectSnapshotCommand<VolumeRenderCommand, VolumeRenderParams, VolumeSnapshotCommand> {
  static Schema declare();
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
