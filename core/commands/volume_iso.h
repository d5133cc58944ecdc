// `volume.iso` — sets the iso-level c of a volume's surface D = c (seed Eq. 7.1), and optionally further iso-levels
// whose silhouettes are drawn with it (seed Figs. 7.4–7.6, 7.9, 7.12: skin and bone, or several grey levels, each with
// its own stroke style and colour). Fields: declared in volume_iso.cpp (ParamSchema), listed in docs/commands.md.
// "levels" lists every level, the first being the surface: [c0, c1, …] or [{"level":c,"style":S,"color":[r,g,b]},
// …]; the first entry's style and colour, when given, set the volume's silhouette style and surface colour, the
// others' are the strokes of their silhouettes (default: plain, a distinct colour per level). Without "levels" the
// further levels are kept. A level outside the values D takes is allowed (nothing is shown) and reported (stats
// in_range = false). When the volume's silhouettes are enabled they are extracted again for the scene camera, every
// level's (the singleton table is reused: no new preprocessing). stats(): level, in_range, cells (singletons holding
// the level), levels (how many), and the silhouette figures when enabled.
// Errors beyond the declared ranges (CommandError, field named): neither level nor levels, a level that differs from
// levels[0] ("level"); an empty list, more than kMaxVolumeLevels entries, an entry that is not a finite number or an
// object of those fields, an unknown style, a colour outside [0,1]³ ("levels").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

// One entry of volume.iso's "levels": the value, and the stroke style and colour when given.
struct VolumeLevelSpec {
  double level = 0.0;
  std::optional<std::string> style;
  std::optional<glm::vec3> color;
};

struct VolumeIsoParams {
  std::string object;
  std::optional<double> level;                         // the first level; may be left out when levels is given
  std::optional<std::vector<VolumeLevelSpec>> levels;  // every level, the first the surface; unset = kept
};

struct VolumeIsoCommand : ObjectSnapshotCommand<VolumeIsoCommand, VolumeIsoParams, VolumeSnapshotCommand> {
  static Schema declare();
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
