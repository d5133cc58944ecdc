#include "core/commands/dffd_cut.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/commands/json_fields.h"
#include "core/dffd/dffd.h"

namespace trispline::core {
namespace jf = json_fields;

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

CommandPtr DffdCutCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DffdCutCommand>();
  c->object_ = jf::get_string(j, "object");
  const std::string axis = jf::get_enum(j, "axis", {"u", "v", "w"}, "u");
  c->axis_ = axis == "u" ? 0 : axis == "v" ? 1 : 2;
  c->at_ = jf::get_number(j, "at");
  c->gap_ = jf::get_number(j, "gap", 0.0);
  if (std::abs(c->gap_) > 100.0) throw CommandError("field 'gap': |gap| must be ≤ 100 world units", "gap");
  c->eps_ = jf::get_number(j, "eps", 1e-6);
  if (!(c->eps_ > 0.0 && c->eps_ <= 1e-3)) throw CommandError("field 'eps': must be in (0, 1e-3]", "eps");
  return c;
}

nlohmann::json DffdCutCommand::to_json() const {
  return {{"cmd", id()}, {"object", object_}, {"axis", kAxisNames[axis_]}, {"at", at_}, {"gap", gap_}, {"eps", eps_}};
}

std::string DffdCutCommand::label() const {
  char buf[64];
  std::snprintf(buf, sizeof buf, " at %s = %g", kAxisNames[axis_], at_);
  return "Cut '" + object_ + "'" + buf;
}

std::optional<SceneObject> DffdCutCommand::build(const Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, object_);
  if (object.clip)
    throw CommandError("field 'object': '" + object_ + "' plays a glTF clip; cutting would break its vertex "
                       "correspondence (remove the clip first)", "object");
  const auto t0 = std::chrono::steady_clock::now();
  auto binding = std::make_shared<FfdBinding>(*object.ffd);
  Discontinuity disc;
  try {
    disc = insert_discontinuity(binding->lattice, axis_, at_);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'at': ") + e.what(), "at");
  }
  MeshSplit split = split_mesh_at_parameter(*object.rest_mesh, object.ffd->params, axis_, at_, eps_);
  if (gap_ != 0.0) {
    const int last = binding->lattice.control_counts()[axis_] - 1;
    const glm::dvec3 a = plane_centroid(binding->lattice, axis_, std::max(0, disc.minus_plane - 1));
    const glm::dvec3 b = plane_centroid(binding->lattice, axis_, std::min(last, disc.plus_plane + 1));
    const double len = glm::length(b - a);
    if (!(len > 0.0))
      throw CommandError("field 'at': the lattice has no extent along " + std::string(kAxisNames[axis_]) +
                         " at the cut, so the opening has no direction", "at");
    const glm::dvec3 d = (b - a) / len;
    open_discontinuity(binding->lattice, disc, -0.5 * gap_ * d, 0.5 * gap_ * d);
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
