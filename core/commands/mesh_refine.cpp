#include "core/commands/mesh_refine.h"

#include <chrono>
#include <cmath>

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

CommandPtr MeshRefineCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<MeshRefineCommand>();
  RefineOptions& o = c->options_;
  c->object_ = jf::get_string(j, "object");
  o.tolerance = jf::get_number(j, "tolerance");
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
    throw CommandError("field 'tolerance': must be a finite distance > 0 (world units)", "tolerance");
  o.criterion = parse_refine_criterion(jf::get_enum(j, "criterion", {"midpoint", "greville"}, "greville"));
  o.max_iterations = jf::get_int(j, "max_iterations", 16);
  if (o.max_iterations < 0 || o.max_iterations > 64)
    throw CommandError("field 'max_iterations': must be in 0..64", "max_iterations");
  const std::int64_t max_tris = jf::get_int64(j, "max_triangles", 2'000'000);
  // A refined triangle costs ~400 bytes across the mesh, its FFD parameters, the evaluated copy and the edge tables:
  // 8 M triangles stay near 3 GiB (50 M reached 7 GB).
  if (max_tris < 1 || max_tris > 8'000'000)
    throw CommandError("field 'max_triangles': must be in 1..8000000 (the memory budget of a refinement)",
                       "max_triangles");
  o.max_triangles = static_cast<std::size_t>(max_tris);
  return c;
}

nlohmann::json MeshRefineCommand::to_json() const {
  return {{"cmd", id()},
          {"object", object_},
          {"tolerance", options_.tolerance},
          {"criterion", refine_criterion_name(options_.criterion)},
          {"max_iterations", options_.max_iterations},
          {"max_triangles", options_.max_triangles}};
}

std::optional<SceneObject> MeshRefineCommand::build(const Scene& scene) {
  const SceneObject* target = &require_deformed_object(scene, object_);
  if (options_.max_triangles < target->rest_mesh->triangles.size())
    throw CommandError("field 'max_triangles': " + std::to_string(options_.max_triangles) + " is below the " +
                           std::to_string(target->rest_mesh->triangles.size()) + " triangles of '" + object_ + "'",
                       "max_triangles");
  if (target->clip)
    throw CommandError("field 'object': '" + object_ + "' plays a glTF clip that animates its vertices; refining would "
                       "break the clip's vertex correspondence (remove the clip with anim.clip \"remove\":true first)",
                       "object");
  RefineOptions o = options_;
  o.param_offset = target->offset_at(0.0);
  const auto t0 = std::chrono::steady_clock::now();
  // Object space: the transform and the embedding are affine, so the splits are the same points as in world space.
  RefineResult r = refine_for_ffd(*target->rest_mesh, *target->ffd, o);
  const auto t1 = std::chrono::steady_clock::now();
  SceneObject out = *target;
  auto binding = std::make_shared<FfdBinding>(*target->ffd);
  binding->params = std::move(r.params);
  out.ffd = std::move(binding);
  out.rest_mesh = std::make_shared<const TriMesh>(std::move(r.mesh));
  out.refresh();
  const auto t2 = std::chrono::steady_clock::now();
  using ms = std::chrono::duration<double, std::milli>;
  const RefineStats& s = r.stats;
  stats_ = {{"criterion", refine_criterion_name(options_.criterion)},
            {"tolerance", options_.tolerance},
            {"triangles_before", s.triangles_before},
            {"triangles_after", s.triangles_after},
            {"vertices_before", s.vertices_before},
            {"vertices_after", s.vertices_after},
            {"iterations", s.iterations},
            {"max_midpoint_error", s.max_midpoint_error},
            {"max_deviation_bound", s.max_deviation_bound},
            {"stopped_by_budget", s.stopped_by_budget},
            {"stopped_by", s.stopped_by},
            {"ms_refine", ms(t1 - t0).count()},
            {"ms_evaluate", ms(t2 - t1).count()}};
  return out;
}

}  // namespace trispline::core
