// `ddm.animate` — a DDM layer's animation (seed §5.4.2): texture-space offset, rotation and scale of its tiles, their
// w (height along the base normal) and metamorphosis between two tiles of the same topology (Eq. 5.3), played on the
// timeline and recorded like any animation. Rotation and scale turn each tile about its cell's centre, on top of the
// layer's own transform (ddm.fill's rotate_deg, scale); w > 0 multiplies the layer's height.
// Fields: declared in ddm_animate.cpp (ParamSchema), listed in docs/commands.md. A field given replaces that part of
// the layer's animation, the others are kept. Morph tiles are logged absolute, relative in saved logs; each must have
// its tile's vertex count and triangles. The keys' frames are converted with the current timeline, like
// anim.keyframe's. The metamorphosis is V = V1·(1 − α) + V2·α with renormalised normals; α outside [0, 1]
// extrapolates. The offset at time t is the offset keys' value plus offset_velocity·t; on the teapot body's periodic
// chart du = 1 is one turn round the pot.
// The layer's mesh is re-evaluated at scene time 0; scene_at_time evaluates it at any time (replay --time,
// anim.record), the renderer plays it on the GPU.
// Errors beyond the declared ranges (CommandError, field named; the scene is unchanged): unknown object or layer,
// morph tile of another topology, unreadable, or not one per tile of the layer ("morph_tile"), alpha keys without a
// morph tile ("alpha_keys"), two keys on one frame.
// report.json: alpha_keys, offset_keys, rotate_keys, scale_keys, w_keys, morph (bool), vertices.
#pragma once

#include "core/commands/ddm_layer_spec.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmAnimateParams {
  std::string object, layer;
  bool clear = false;  // remove the layer's animation before the fields below apply
  // "morph_tile" (one) or "morph_tiles" (one per tile) as given; {""} removes the metamorphosis; unset = kept.
  std::optional<std::vector<std::string>> morph;
  std::vector<std::filesystem::path> morph_paths;      // per morph tile: the resolved file (parse), empty if none
  std::optional<std::vector<glm::dvec2>> alpha_keys;   // (frame, α)
  std::optional<std::vector<glm::dvec3>> offset_keys;  // (frame, du, dv)
  std::optional<glm::dvec2> offset_velocity;           // chart units per second
  std::optional<std::vector<glm::dvec2>> rotate_keys;  // (frame, degrees added to the layer's rotate_deg)
  std::optional<std::vector<glm::dvec2>> scale_keys;   // (frame, factor on the layer's scale), > 0
  std::optional<std::vector<glm::dvec2>> w_keys;       // (frame, factor on the layer's height), > 0
  std::optional<double> alpha;
  std::string interpolation = "linear";  // of this line's keys: "linear" | "constant" | "smooth"
};

struct DdmAnimateCommand : ObjectSnapshotCommand<DdmAnimateCommand, DdmAnimateParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
