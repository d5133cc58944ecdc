#include "core/commands/lattice_set_point.h"

#include <chrono>
#include <cmath>

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr LatticeSetPointCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<LatticeSetPointCommand>();
  c->object_ = jf::get_string(j, "object");
  c->index_ = jf::get_ivec3(j, "index");
  c->position_ = jf::get_vec3(j, "position");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(c->position_[a]))
      throw CommandError("field 'position': expected 3 finite numbers (world units)", "position");
  return c;
}

nlohmann::json LatticeSetPointCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"index", jf::to_json(index_)}, {"position", jf::to_json(position_)}};
}

std::string LatticeSetPointCommand::label() const {
  return "Set control point (" + std::to_string(index_.x) + ", " + std::to_string(index_.y) + ", " +
         std::to_string(index_.z) + ") of '" + object_ + "'";
}

std::optional<SceneObject> LatticeSetPointCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, object_);
  const glm::ivec3 n = object.ffd->lattice.control_counts();
  for (int a = 0; a < 3; ++a)
    if (index_[a] < 0 || index_[a] >= n[a])
      throw CommandError("field 'index': [" + std::to_string(index_.x) + ", " + std::to_string(index_.y) + ", " +
                             std::to_string(index_.z) + "] is outside the " + std::to_string(n.x) + " x " +
                             std::to_string(n.y) + " x " + std::to_string(n.z) + " control points of '" + object_ +
                             "'",
                         "index");
  TrivariateBSpline<glm::dvec3> lattice = object.ffd->lattice;
  glm::dvec3& p = lattice.control_point(index_.x, index_.y, index_.z);
  const double displacement = glm::length(position_ - p);
  p = position_;
  SceneObject out = object;
  out.ffd = std::make_shared<FfdBinding>(FfdBinding{std::move(lattice), object.ffd->embedding, object.ffd->params});
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();
  stats_ = {{"moved", displacement > 0.0 ? 1 : 0},
            {"displacement", displacement},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
