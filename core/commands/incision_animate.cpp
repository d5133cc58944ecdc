// incision.animate. See incision_animate.h. Source: seed §6.4 (the opening of an incision).
#include "core/commands/incision_animate.h"

#include <algorithm>
#include <cmath>

#include "core/commands/anim_keys.h"

namespace trispline::core {

auto IncisionAnimateCommand::declare() -> Schema {
  return keyed_weight_schema(
             {"incision.animate", "Key an incision's opening on the timeline: 0 closed, 1 as drawn (seed §6.4)",
              "An object cut by incision.draw", "Remove the keys: the incision shows fully open", "opening_keys",
              "[timeline frame, s] keys: s = fraction of the drawn opening (0 closed, 1 as drawn)", "opening"})
      .label([](const P& p) {
        return p.clear && !p.keys ? "Open incision of '" + p.object + "'" : "Animate incision of '" + p.object + "'";
      })
      .failure_field("opening_keys");
}

std::optional<SceneObject> IncisionAnimateCommand::build(const Scene& scene) {
  const SceneObject& object = require_object(scene, p_.object);
  if (!object.morph)
    throw CommandError("field 'object': '" + p_.object + "' has no incision to animate (cut it with incision.draw)",
                       "object");
  if (object.ffd || object.dffd)
    throw CommandError("field 'object': '" + p_.object + "' is deformed (FFD or DFFD); key the incision before placing",
                       "object");
  auto morph = std::make_shared<MorphChannel>(*object.morph);
  morph->weight_keys = {OffsetKey{0.0, glm::dvec3(1.0, 0.0, 0.0), KeyInterpolation::constant}};
  if (p_.keys) morph->weight_keys = keyed_weights(p_, scene.timeline, "opening_keys");
  SceneObject out = object;
  out.morph = std::move(morph);
  out.refresh();
  stats_ = {{"keys", out.morph->weight_keys.size()}, {"opening_at_start", out.morph->weight_at(0.0)}};
  return out;
}

}  // namespace trispline::core
