// `volume.silhouettes` — turns a volume's silhouettes on or off and sets how they are found and stroked (seed §7.3),
// extracting them for the scene camera.
//   {"cmd":"volume.silhouettes","object":"ID","enabled":true,"style":"hue","hidden":"remove",
//    "projection":"perspective","subdivision":1,"accuracy":1e-7}
// style: hue | glyphs | width | plain (the seed's three stroke styles, Fig. 7.10–7.12, and black). hidden: remove |
// dashed | show (parts occluded by the iso-surface). projection: perspective (G·(P − eye) = 0) or orthographic
// (G·forward = 0) for the camera. subdivision (1…4) and accuracy (1e-12…1e-2) are the seed's two parameters.
// stats(): points, polylines, length_mm, candidates, seeds, extract_ms, hidden_ms, max_value_residual,
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

class VolumeSilhouettesCommand
    : public DeclaredCommand<VolumeSilhouettesCommand, VolumeSilhouettesParams, VolumeSnapshotCommand> {
 public:
  using DeclaredCommand::DeclaredCommand;
  static const ParamSchema<VolumeSilhouettesParams>& schema();
  std::string label() const override {
    return std::string(p_.enabled ? "Silhouettes of '" : "Hide silhouettes of '") + p_.object + "'";
  }

 protected:
  std::string target() const override { return p_.object; }
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
