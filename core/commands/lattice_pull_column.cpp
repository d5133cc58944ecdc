#include "core/commands/lattice_pull_column.h"

#include <cmath>
#include <stdexcept>

#include "core/placement/pressing.h"

namespace trispline::core {

auto LatticePullColumnCommand::declare() -> Schema {
  return Schema("lattice.pull_column", "Pull or push one contact control point and its column along V_P (seed §2.4.1)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD)"})
      .field("column", &P::column, {.required = true, .help = "(i, j) of the contact control point"})
      .field("distance", &P::distance, {.required = true, .unit = "world units", .help = "Move along V_P; < 0 pushes"})
      .label([](const P& p) {
        return "Pull column (" + std::to_string(p.column.x) + ", " + std::to_string(p.column.y) + ") of '" + p.object +
               "'";
      });
}

std::optional<SceneObject> LatticePullColumnCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  TrivariateBSpline<glm::dvec3> after = object.ffd->lattice;
  const glm::ivec3 counts = after.control_counts();
  if (p_.column.x < 0 || p_.column.y < 0 || p_.column.x >= counts.x || p_.column.y >= counts.y)
    throw CommandError("field 'column': (" + std::to_string(p_.column.x) + ", " + std::to_string(p_.column.y) +
                           ") is outside the " + std::to_string(counts.x) + " x " + std::to_string(counts.y) +
                           " columns of the lattice",
                       "column");
  const glm::dvec3 vp = [&] {
    try {
      return column_direction(after, p_.column.x, p_.column.y);
    } catch (const std::invalid_argument& e) {  // every column of zero length
      throw CommandError("field 'object': " + std::string(e.what()), "object");
    }
  }();
  const int n = after.control_counts().z;
  for (int k = 0; k < n; ++k) after.control_point(p_.column.x, p_.column.y, k) += p_.distance * vp;
  stats_ = {{"moved", n}, {"max_displacement", std::abs(p_.distance)}};
  return with_lattice(object, std::move(after), stats_);
}

}  // namespace trispline::core
