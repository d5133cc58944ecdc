#include "core/commands/lattice_set_point.h"

#include <chrono>
#include <cmath>

namespace trispline::core {

auto LatticeSetPointCommand::declare() -> Schema {
  return Schema("lattice.set_point", "Move one control point of a deformed object's lattice to an exact position")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD)"})
      .field("index", &P::index, {.required = true, .help = "(i, j, k) of the control point, each inside the lattice"})
      .field("position", &P::position,
             {.required = true, .unit = "world units", .help = "Where the control point goes"})
      .label([](const P& p) {
        return "Set control point (" + std::to_string(p.index.x) + ", " + std::to_string(p.index.y) + ", " +
               std::to_string(p.index.z) + ") of '" + p.object + "'";
      });
}

std::optional<SceneObject> LatticeSetPointCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  const glm::ivec3 n = object.ffd->lattice.control_counts();
  for (int a = 0; a < 3; ++a)
    if (p_.index[a] < 0 || p_.index[a] >= n[a])
      throw CommandError("field 'index': [" + std::to_string(p_.index.x) + ", " + std::to_string(p_.index.y) + ", " +
                             std::to_string(p_.index.z) + "] is outside the " + std::to_string(n.x) + " x " +
                             std::to_string(n.y) + " x " + std::to_string(n.z) + " control points of '" + p_.object +
                             "'",
                         "index");
  TrivariateBSpline<glm::dvec3> lattice = object.ffd->lattice;
  glm::dvec3& p = lattice.control_point(p_.index.x, p_.index.y, p_.index.z);
  const double displacement = glm::length(p_.position - p);
  p = p_.position;
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
