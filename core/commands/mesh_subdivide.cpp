#include "core/commands/mesh_subdivide.h"

#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/mesh/mesh_io.h"

namespace trispline::core {

namespace {

constexpr int kMaxLevels = 4;
constexpr std::size_t kMaxTriangles = 8'000'000;

}  // namespace

auto MeshSubdivideCommand::declare() -> Schema {
  return Schema("mesh.subdivide", "Subdivide an object's rest mesh uniformly (Loop, OpenSubdiv), before deforming it")
      .field("object", &P::object, {.required = true, .help = "An undeformed object without tile layers"})
      .field("levels", &P::levels,
             {.range = ParamRange{1, kMaxLevels}, .help = "Subdivision levels; each quadruples the triangles"})
      .choice("scheme", &P::scheme, {"loop"}, {.help = "Loop subdivision of the triangles (OpenSubdiv Far)"})
      .label([](const P& p) {
        return "Subdivide '" + p.object + "' (Loop, " + std::to_string(p.levels) +
               (p.levels == 1 ? " level)" : " levels)");
      });
}

std::optional<SceneObject> MeshSubdivideCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  require_no_tile_layers(*object, "a subdivision");
  const char* deformed = object->ffd    ? "an FFD lattice"
                         : object->dffd ? "a DFFD split"
                         : object->clip ? "a glTF clip"
                                        : nullptr;
  if (deformed)
    throw CommandError("field 'object': '" + p_.object + "' has " + deformed + " bound to its vertices; subdivide " +
                           "before deforming (mesh.subdivide first, then place.sketch / lattice.ring / dffd.* / " +
                           "anim.clip)",
                       "object");
  const TriMesh& rest = *object->rest_mesh;
  const std::size_t tris = rest.triangle_count() << (2 * p_.levels);
  if (tris > kMaxTriangles)
    throw CommandError("field 'levels': " + std::to_string(p_.levels) + " levels would make " + std::to_string(tris) +
                           " triangles (at most " + std::to_string(kMaxTriangles) + ")",
                       "levels");
  const auto t0 = std::chrono::steady_clock::now();
  TriMesh sub;
  try {
    sub = loop_subdivide(rest, p_.levels);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'object': ") + e.what(), "object");
  }
  SceneObject out = *object;
  out.rest_mesh = std::make_shared<const TriMesh>(std::move(sub));
  out.refresh();
  stats_ = {{"levels", p_.levels},
            {"vertices_before", rest.vertex_count()},
            {"vertices_after", out.rest_mesh->vertex_count()},
            {"triangles_before", rest.triangle_count()},
            {"triangles_after", out.rest_mesh->triangle_count()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
