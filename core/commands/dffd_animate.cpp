// dffd.animate. See dffd_animate.h. Source: seed §6.3.2 (openings and stitching of a discontinuous FFD).
#include "core/commands/dffd_animate.h"

#include <cmath>

#include "core/commands/anim_keys.h"

namespace trispline::core {

auto DffdAnimateCommand::declare() -> Schema {
  return keyed_weight_schema(
             {"dffd.animate", "Key a DFFD's seam on the timeline: 0 the openings capped, 1 stitched (seed §6.3.2)",
              "An object split by dffd.split with openings cap or stitch",
              "Remove the keys: the seam as dffd.split built it", "stitch_keys",
              "[timeline frame, s] keys: s = 0 the openings as the obstacles leave them, 1 stitched at w_s",
              "stitched seam"})
      .label([](const P& p) {
        return p.clear && !p.keys ? "Reset seam of '" + p.object + "'" : "Animate seam of '" + p.object + "'";
      })
      .failure_field("stitch_keys");
}

std::optional<SceneObject> DffdAnimateCommand::build(const Scene& scene) {
  const SceneObject& object = require_object(scene, p_.object);
  if (!object.dffd)
    throw CommandError("field 'object': '" + p_.object + "' is not split by a DFFD (split it with dffd.split)",
                       "object");
  if (!object.dffd->seam)
    throw CommandError("field 'object': '" + p_.object +
                           "' was split with \"openings\":\"open\": its openings have no "
                           "caps, so there is no seam to stitch (split it with openings cap or stitch)",
                       "object");
  auto rig = std::make_shared<DffdRig>(*object.dffd);
  rig->stitch_keys = keyed_weights(p_, scene.timeline, "stitch_keys");
  const double start = dffd_stitch_at(*rig, 0.0);
  dffd_set_stitch(*rig, start);  // the lattice shows scene time 0 (the built state after a clear)
  SceneObject out = object;
  out.dffd = std::move(rig);
  out.refresh();
  stats_ = {{"keys", out.dffd->stitch_keys.size()}, {"stitch_at_start", start}};
  return out;
}

}  // namespace trispline::core
