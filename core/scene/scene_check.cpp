#include "core/scene/scene_check.h"

#include <cmath>

namespace trispline::core {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool in_range(const glm::dvec3& v) {
  return finite(v) && std::abs(v.x) <= kMaxWorldCoordinate && std::abs(v.y) <= kMaxWorldCoordinate &&
         std::abs(v.z) <= kMaxWorldCoordinate;
}

std::string mesh_error(const TriMesh& mesh, const std::string& what) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!in_range(mesh.positions[i]))
      return what + ": vertex " + std::to_string(i) +
             (finite(mesh.positions[i]) ? " lies beyond ±1e12 world units" : " is not finite");
  for (std::size_t i = 0; i < mesh.normals.size(); ++i)
    if (!finite(mesh.normals[i])) return what + ": the normal of vertex " + std::to_string(i) + " is not finite";
  return {};
}

}  // namespace

std::string scene_value_error(const Scene& scene, const std::set<const void*>& unchanged) {
  auto seen = [&](const void* p) { return p == nullptr || unchanged.count(p) != 0; };
  const Camera& c = scene.camera;
  if (!finite(c.eye) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.fov_deg))
    return "the camera is not finite";
  if (!(scene.timeline.fps > 0) || !std::isfinite(scene.timeline.duration_s()))
    return "the timeline's duration is not finite";
  for (const SceneObject& o : scene.objects()) {
    const std::string name = "object '" + o.name + "'";
    const Transform& t = o.transform;
    if (!in_range(t.translate) || !finite(t.rotate_deg) || !in_range(t.scale))
      return name + ": its transform is not finite or beyond ±1e12";
    if (!finite(o.param_offset) || !finite(o.offset_velocity)) return name + ": its parameter offset is not finite";
    for (const OffsetKey& k : o.offset_keys)
      if (!std::isfinite(k.time_s) || !finite(k.offset)) return name + ": an offset key is not finite";
    if (!seen(o.world_mesh.get()))
      if (std::string e = mesh_error(*o.world_mesh, "the mesh of " + name); !e.empty()) return e;
    if (!seen(o.ffd.get()))
      for (const glm::dvec3& p : o.ffd->lattice.control_points())
        if (!in_range(p)) return name + ": a lattice control point is not finite or beyond ±1e12 world units";
    for (const auto& layer : o.ddm_layers)
      if (layer && !seen(layer.get()) && layer->mesh)
        if (std::string e = mesh_error(*layer->mesh, "tile layer '" + layer->name + "' of " + name); !e.empty())
          return e;
  }
  return {};
}

SceneGuard::SceneGuard(const Scene& scene) {
  for (const SceneObject& o : scene.objects()) {
    before_.insert(o.world_mesh.get());
    before_.insert(o.ffd.get());
    for (const auto& layer : o.ddm_layers) before_.insert(layer.get());
  }
}

std::string SceneGuard::error(const Scene& scene) const { return scene_value_error(scene, before_); }

}  // namespace trispline::core
