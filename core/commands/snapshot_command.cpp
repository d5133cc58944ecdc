#include "core/commands/snapshot_command.h"

#include <chrono>

namespace trispline::core {

const SceneObject& require_object(const Scene& scene, const std::string& name, const char* field) {
  const SceneObject* o = scene.find(name);
  if (!o) throw CommandError("field '" + std::string(field) + "': no object named '" + name + "'", field);
  return *o;
}

const SceneObject& require_deformed_object(const Scene& scene, const std::string& name) {
  const SceneObject* o = &require_object(scene, name);
  if (!o->ffd)
    throw CommandError(
        "field 'object': '" + name + "' has no FFD lattice (place it with place.sketch or lattice.ring first)",
        "object");
  return *o;
}

std::vector<glm::dvec3> positions_with_tile_layers(const SceneObject& object, const TriMesh& world_rest) {
  std::vector<glm::dvec3> out = world_rest.positions;
  const glm::dmat4 m = object.transform.matrix();
  for (const auto& layer : object.ddm_layers)
    if (layer && layer->mesh)
      for (const glm::dvec3& p : layer->mesh->positions) out.push_back(glm::dvec3(m * glm::dvec4(p, 1.0)));
  return out;
}

void require_no_tile_layers(const SceneObject& object, const std::string& change) {
  if (object.ddm_layers.empty()) return;
  std::string names;
  for (const auto& layer : object.ddm_layers) names += (names.empty() ? "" : ", ") + layer->name;
  throw CommandError("field 'object': '" + object.name + "' holds tile layers (" + names +
                         ") laid on its current mesh, which " + change +
                         " would replace; bake them (ddm.bake) or remove them (ddm.remove) first",
                     "object");
}

SceneObject with_lattice(const SceneObject& object, TrivariateBSpline<glm::dvec3> lattice, nlohmann::json& stats) {
  SceneObject out = object;
  out.ffd = std::make_shared<FfdBinding>(FfdBinding{std::move(lattice), object.ffd->embedding, object.ffd->params});
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();
  stats["ms_evaluate"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace trispline::core
