// `volume.silhouettes` — turns a volume's silhouettes on or off and sets how they are found and stroked (seed §7.3),
// extracting them for the scene camera. Fields: declared in volume_silhouettes.cpp (ParamSchema), listed in
// docs/commands.md. The styles hue, glyphs and width are the seed's three stroke styles (Fig. 7.10–7.12), plain is
// black, chromadepth colours by depth for ChromaDepth glasses (Figs. 7.8–7.9). A silhouette point lies on D = c with
// G·(P − eye) = 0 (perspective) or G·forward = 0 (orthographic) for the camera. subdivision and accuracy are the seed's
// two parameters. stats(): points, polylines, length_mm, candidates, seeds, extract_ms, hidden_ms, max_value_residual,
// max_dot_residual (absent when disabled).
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

struct VolumeSilhouettesParams {
  std::string object;
  bool enabled = true;
  std::string style = "hue", hidden = "remove", projection = "perspective";
  int subdivision = 1;
  double accuracy = 1e-7;
};

struct VolumeSilhouettesCommand
    : ObjectSnapshotCommand<VolumeSilhouettesCommand, VolumeSilhouettesParams, VolumeSnapshotCommand> {
  static Schema declare();
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
