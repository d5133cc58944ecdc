#include "core/commands/volume_silhouettes.h"

namespace trispline::core {

auto VolumeSilhouettesCommand::declare() -> Schema {
  return Schema("volume.silhouettes", "Show a volume's smooth silhouettes for the current view (seed §7.3)")
      .field("object", &P::object, {.required = true, .help = "A volume"})
      .field("enabled", &P::enabled, {.help = "Extract and draw the silhouettes (false hides them)"})
      .choice(
          "style", &P::style, {"hue", "glyphs", "fans", "width", "plain", "chromadepth"},
          {.ui = {"Style"},
           .help = "hue: colour by gradient magnitude; glyphs: short strokes along the curve, longer where the "
                   "gradient is larger; fans: fans across the curve, narrower and bluer where the gradient is larger "
                   "(Fig. 7.11); width: stroke width and grey by gradient magnitude; plain: black lines; chromadepth: "
                   "colour by depth, red nearest to blue farthest, for ChromaDepth glasses (Figs. 7.8–7.9)"})
      .choice("hidden", &P::hidden, {"remove", "dashed", "show"},
              {.ui = {"Hidden lines"},
               .help = "Parts hidden behind the iso-surface: removed, dashed, or shown like the rest"})
      .choice("projection", &P::projection, {"perspective", "orthographic"},
              {.ui = {"Projection"}, .help = "perspective: G·(P − eye) = 0; orthographic: G·(view direction) = 0"})
      .field("subdivision", &P::subdivision,
             {.range = ParamRange{1, 4},
              .ui = {"Subdivision"},
              .help = "Newton seeds per singleton axis (the seed's subdivision parameter)"})
      .field("accuracy", &P::accuracy,
             {.range = ParamRange{1e-12, 1e-2},
              .ui = {"Accuracy"},
              .help = "Newton stops when |D − c| ≤ accuracy·range(D) and |G·V| ≤ accuracy·|G|·|V|"})
      .label([](const P& p) {
        return std::string(p.enabled ? "Silhouettes of '" : "Hide silhouettes of '") + p.object + "'";
      });
}

std::optional<VolumeObject> VolumeSilhouettesCommand::build(const Scene& scene) {
  VolumeObject v = require_volume(scene, p_.object);
  v.silhouette.enabled = p_.enabled;
  v.silhouette.style = p_.style;
  v.silhouette.hidden = p_.hidden;
  v.silhouette.projection = p_.projection;
  v.silhouette.params.subdivision = p_.subdivision;
  v.silhouette.params.accuracy = p_.accuracy;
  return volume_with_silhouettes(v, scene.camera, &stats_);
}

}  // namespace trispline::core
