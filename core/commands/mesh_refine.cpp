#include "core/commands/mesh_refine.h"

#include <chrono>
#include <cmath>

#include "core/ffd/deformation_bounds.h"

namespace trispline::core {

auto MeshRefineCommand::declare() -> Schema {
  return Schema("mesh.refine", "Refine a deformed object's mesh until its edges follow the FFD (seed §2.4.2)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD), without a glTF clip"})
      .field("tolerance", &P::tolerance,
             {.required = true,
              .range = ParamRange::above(0),
              .unit = "world units",
              .help = "Largest distance of a deformed edge from its straight chord"})
      .choice("criterion", &P::criterion, {"midpoint", "greville", "best"},
              {.help = "midpoint: the seed's Eq. 2.6 estimate at edge midpoints; greville: a bound from the edge "
                       "curve's control points, split at the farthest one; best (with error bound): each triangle "
                       "takes the split (1 → 4, or its longest edge halved) whose children need the fewest triangles"})
      .choice("error", &P::error, {"edge", "bound"},
              {.help = "edge: hold each edge's measure (the criterion's) to the tolerance; bound: hold each triangle's "
                       "certified deformation-error bound (seed §3.2) to it, splitting where the criterion says"})
      .field("max_iterations", &P::max_iterations, {.range = ParamRange{0, 64}, .help = "Split rounds at most"})
      // A refined triangle costs ~400 bytes across the mesh, its FFD parameters, the evaluated copy and the edge
      // tables: 8 M triangles stay near 3 GiB (50 M reached 7 GB).
      .field("max_triangles", &P::max_triangles,
             {.range = ParamRange{1, 8'000'000},
              .help = "The memory budget of a refinement: a round that would exceed it is not applied; ≥ the "
                      "input's triangles"})
      .label([](const P& p) { return "Refine '" + p.object + "' for its FFD"; });
}

RefineOptions MeshRefineCommand::options() const {
  RefineOptions o;
  o.tolerance = p_.tolerance;
  o.criterion = parse_refine_criterion(p_.criterion);
  o.error = p_.error == "bound" ? RefineError::bound : RefineError::edge;
  o.max_iterations = p_.max_iterations;
  o.max_triangles = static_cast<std::size_t>(p_.max_triangles);
  return o;
}

std::optional<SceneObject> MeshRefineCommand::build(const Scene& scene) {
  const RefineOptions opts = options();
  const SceneObject* target = &require_deformed_object(scene, p_.object);
  if (opts.max_triangles < target->rest_mesh->triangles.size())
    throw CommandError("field 'max_triangles': " + std::to_string(opts.max_triangles) + " is below the " +
                           std::to_string(target->rest_mesh->triangles.size()) + " triangles of '" + p_.object + "'",
                       "max_triangles");
  {
    // A tolerance below float32's resolution at the object's size cannot be met in scene.glb nor seen; only the
    // triangle budget would stop it (tolerance 1e-300: every round splits every triangle).
    Aabb box;
    if (target->world_mesh)
      for (const glm::dvec3& p : target->world_mesh->positions) box.extend(p);
    const double floor = kMinRefineTolerance * box.diagonal();
    if (opts.tolerance < floor)
      throw CommandError("field 'tolerance': " + params::format_number(opts.tolerance) + " world units is below " +
                             params::format_number(floor) + " (1e-7 × the size of '" + p_.object +
                             "', float32's resolution there): no refinement can meet it",
                         "tolerance");
  }
  if (target->clip)
    throw CommandError(
        "field 'object': '" + p_.object +
            "' plays a glTF clip that animates its vertices; refining would "
            "break the clip's vertex correspondence (remove the clip with anim.clip \"remove\":true first)",
        "object");
  if (opts.criterion == RefineCriterion::Best && opts.error != RefineError::bound)
    throw CommandError(
        "field 'criterion': \"best\" chooses each split by the certified bound: use it with "
        "\"error\":\"bound\"",
        "criterion");
  if (opts.error == RefineError::bound) {
    try {
      SecondDerivativeBounds check(target->ffd->lattice);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("field 'error': ") + e.what() + " (use \"error\":\"edge\")", "error");
    }
  }
  RefineOptions o = opts;
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
  stats_ = {{"criterion", refine_criterion_name(opts.criterion)},
            {"tolerance", opts.tolerance},
            {"triangles_before", s.triangles_before},
            {"triangles_after", s.triangles_after},
            {"vertices_before", s.vertices_before},
            {"vertices_after", s.vertices_after},
            {"iterations", s.iterations},
            {"max_midpoint_error", s.max_midpoint_error},
            {"max_deviation_bound", s.max_deviation_bound},
            {"stopped_by_budget", s.stopped_by_budget},
            {"stopped_by", s.stopped_by},
            {"error", p_.error},
            {"ms_refine", ms(t1 - t0).count()},
            {"ms_evaluate", ms(t2 - t1).count()}};
  if (opts.error == RefineError::bound) {
    stats_["bound"] = "best of right triangle (Filip et al. Theorem 4) and smallest enclosing circle (Waldron)";
    // +∞ (a triangle across a C⁰ knot plane) is written as null: JSON has no infinity.
    stats_["max_bound"] = std::isfinite(s.max_triangle_bound) ? nlohmann::json(s.max_triangle_bound) : nlohmann::json();
  }
  return out;
}

}  // namespace trispline::core
