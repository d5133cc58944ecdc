// Scene export nodes. See scene_export.h.
#include "core/scene/scene_export.h"

namespace trispline::core {

SceneExport scene_export_nodes(const Scene& scene) {
  SceneExport out;
  for (const SceneObject& o : scene.objects()) {
    if (o.world_mesh) out.nodes.push_back({o.name, o.world_mesh.get(), o.color, o.inside_color});
    for (const auto& layer : o.ddm_layers) {
      if (!layer->mesh) continue;
      auto world = std::make_shared<const TriMesh>(transformed(*layer->mesh, o.transform));
      out.nodes.push_back({o.name + "/" + layer->name, world.get(), layer->color.value_or(o.color), o.inside_color});
      out.owned.push_back(std::move(world));
    }
  }
  return out;
}

}  // namespace trispline::core
