// `ddm.animate` — a DDM layer's animation (seed §5.4.2): texture-space offset of its tiles and metamorphosis
// between two tiles of the same topology (Eq. 5.3), played on the timeline and recorded like any animation.
//
//   {"cmd":"ddm.animate","object":"ID","layer":"NAME","morph_tile":"flower","alpha_keys":[[F,α],...],
//    "offset_keys":[[F,du,dv],...],"offset_velocity":[du,dv],"alpha":a,"interpolation":"linear|constant|smooth"}
//   Every field but object/layer is optional; a given field replaces that part of the layer's animation, the others
//   are kept. {"cmd":"ddm.animate","object":"ID","layer":"NAME","clear":true} removes all of it.
//   morph_tile   the partner of the layer's tile (a generated tile or a mesh file, as ddm.fill's "tile"; logged
//                absolute, relative in saved logs); "morph_tiles":[…] gives one per tile of a several-tile layer;
//                "" removes the metamorphosis. Each must have its tile's vertex count and triangles.
//   alpha_keys   [timeline frame, α] pairs (frames converted with the current timeline, like anim.keyframe);
//                V = V1·(1 − α) + V2·α with renormalised normals; α outside [0, 1] extrapolates. Without keys the
//                layer shows `alpha` (default 0).
//   offset_keys  [frame, du, dv]: the tiles' texture-space offset (chart parameter units; on the teapot body's
//                periodic chart du = 1 is one turn round the pot), plus offset_velocity·t (units per second).
//   interpolation  of the keys given in this line (default linear).
//   The layer's mesh is re-evaluated at scene time 0; scene_at_time evaluates it at any time (replay --time,
//   anim.record), the renderer plays it on the GPU.
// Errors (CommandError, field named; the scene is unchanged): unknown object or layer, morph tile of another
// topology or unreadable ("morph_tile"), alpha keys without a morph tile ("alpha_keys"), non-finite numbers, keys
// that are not [F, α] / [F, du, dv] lists, two keys on one frame.
// report.json: alpha_keys, offset_keys, morph (bool), vertices.
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
  std::optional<double> alpha;
  std::string interpolation = "linear";  // of this line's keys: "linear" | "constant" | "smooth"
};

class DdmAnimateCommand : public ObjectSnapshotCommand<DdmAnimateCommand, DdmAnimateParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<DdmAnimateParams>& schema();
  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string failure_field() const override { return "morph_tile"; }
};

}  // namespace trispline::core
