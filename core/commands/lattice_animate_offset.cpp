#include "core/commands/lattice_animate_offset.h"

#include <chrono>
#include <cmath>

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr LatticeAnimateOffsetCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<LatticeAnimateOffsetCommand>();
  c->object_ = jf::get_string(j, "object");
  c->offset_ = jf::get_vec3(j, "offset", glm::dvec3(0.0));
  c->velocity_ = jf::get_vec3(j, "velocity", glm::dvec3(0.0));
  for (int a = 0; a < 3; ++a) {
    if (std::abs(c->offset_[a]) > 1e6) throw CommandError("field 'offset': |component| must be ≤ 1e6", "offset");
    if (std::abs(c->velocity_[a]) > 100.0)
      throw CommandError("field 'velocity': |component| must be ≤ 100 parameter units per second", "velocity");
  }
  return c;
}

nlohmann::json LatticeAnimateOffsetCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"offset", jf::to_json(offset_)}, {"velocity", jf::to_json(velocity_)}};
}

std::optional<SceneObject> LatticeAnimateOffsetCommand::build(const Scene& scene) {
  const SceneObject* target = &require_deformed_object(scene, object_);
  SceneObject out = *target;
  out.param_offset = offset_;
  out.offset_velocity = velocity_;
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();  // the t = 0 pose at the new offset, CPU double reference
  stats_ = {{"vertices", out.world_mesh->positions.size()},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
