#include "core/commands/lattice_animate_offset.h"

#include <chrono>
#include <cmath>

namespace trispline::core {

auto LatticeAnimateOffsetCommand::declare() -> Schema {
  return Schema("lattice.animate_offset", "Move an object through its lattice over time: parameter offset and velocity")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD)"})
      .field("offset", &P::offset,
             {.range = ParamRange::magnitude_at_most(1e6),
              .unit = "parameter units",
              .help = "Added to the object's lattice parameters; on a periodic axis 1 is one period of the axis "
                      "(one turn of a ring, two on a half-twisted band)"})
      .field("velocity", &P::velocity,
             {.range = ParamRange::magnitude_at_most(100),
              .unit = "parameter units per second",
              .help = "Offset change per second of scene time ([0,0,0] = still)"})
      .label([](const P& p) { return "Animate offset of '" + p.object + "'"; });
}

std::optional<SceneObject> LatticeAnimateOffsetCommand::build(const Scene& scene) {
  const SceneObject* target = &require_deformed_object(scene, p_.object);
  SceneObject out = *target;
  out.param_offset = p_.offset;
  out.offset_velocity = p_.velocity;
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();  // the t = 0 pose at the new offset, CPU double reference
  stats_ = {{"vertices", out.world_mesh->positions.size()},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
