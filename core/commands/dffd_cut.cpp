#include "core/commands/dffd_cut.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/dffd/dffd.h"

namespace trispline::core {

namespace {
const char* kAxisNames[] = {"u", "v", "w"};

// Centroid of the control plane `index` along `axis`.
glm::dvec3 plane_centroid(const TrivariateBSpline<glm::dvec3>& F, int axis, int index) {
  const glm::ivec3 n = F.control_counts();
  glm::dvec3 sum(0.0);
  int count = 0;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const int idx[3] = {i, j, k};
        if (idx[axis] != index) continue;
        sum += F.control_point(i, j, k);
        ++count;
      }
  return sum / double(count);
}
}  // namespace

auto DffdCutCommand::declare() -> Schema {
  return Schema("dffd.cut",
                "Cut a deformed object at a lattice parameter: C⁻¹ knots, exact mesh split, opening (seed §6.3)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD), without a glTF clip"})
      .choice("axis", &P::axis, {"u", "v", "w"}, {.help = "Lattice axis the cut plane is orthogonal to"})
      .field("at", &P::at,
             {.required = true, .unit = "parameter units", .help = "Parameter of the cut, inside the domain"})
      .field("gap", &P::gap,
             {.range = ParamRange::magnitude_at_most(100),
              .unit = "world units",
              .help = "How far the two sides move apart across the cut"})
      .field("eps", &P::eps,
             {.range = ParamRange{0, 1e-3, true, false},
              .unit = "parameter units",
              .help = "Cut vertices sit at at ∓ eps"})
      .label([](const P& p) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " at %s = %g", kAxisNames[p.axis], p.at);
        return "Cut '" + p.object + "'" + buf;
      });
}

std::optional<SceneObject> DffdCutCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  if (object.clip)
    throw CommandError("field 'object': '" + p_.object +
                           "' plays a glTF clip; cutting would break its vertex "
                           "correspondence (remove the clip first)",
                       "object");
  const auto t0 = std::chrono::steady_clock::now();
  auto binding = std::make_shared<FfdBinding>(*object.ffd);
  Discontinuity disc;
  try {
    disc = insert_discontinuity(binding->lattice, p_.axis, p_.at);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'at': ") + e.what(), "at");
  }
  MeshSplit split = split_mesh_at_parameter(*object.rest_mesh, object.ffd->params, p_.axis, p_.at, p_.eps);
  if (p_.gap != 0.0) {
    const int last = binding->lattice.control_counts()[p_.axis] - 1;
    const glm::dvec3 a = plane_centroid(binding->lattice, p_.axis, std::max(0, disc.minus_plane - 1));
    const glm::dvec3 b = plane_centroid(binding->lattice, p_.axis, std::min(last, disc.plus_plane + 1));
    const double len = glm::length(b - a);
    if (!(len > 0.0))
      throw CommandError("field 'at': the lattice has no extent along " + std::string(kAxisNames[p_.axis]) +
                             " at the cut, so the opening has no direction",
                         "at");
    const glm::dvec3 d = (b - a) / len;
    open_discontinuity(binding->lattice, disc, -0.5 * p_.gap * d, 0.5 * p_.gap * d);
  }
  SceneObject out = object;
  const std::size_t before = object.rest_mesh->positions.size();
  binding->params = std::move(split.params);
  out.rest_mesh = std::make_shared<const TriMesh>(std::move(split.mesh));
  out.ffd = std::move(binding);
  out.refresh();
  stats_ = {{"cut_edges", split.cut_edges},
            {"vertices_before", before},
            {"vertices_after", out.rest_mesh->positions.size()},
            {"duplicated_on_plane", split.duplicated_on_plane},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
