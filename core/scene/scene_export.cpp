// Scene export nodes. See scene_export.h.
#include "core/scene/scene_export.h"

#include <glm/gtc/color_space.hpp>

#include "core/scene/ddm_follow.h"
#include "core/volume/silhouette_export.h"

namespace trispline::core {

SceneExport scene_export_nodes(const Scene& scene) {
  SceneExport out;
  for (const SceneObject& o : scene.objects()) {
    if (!o.render_visible) continue;
    if (o.world_mesh) {
      GltfNode node{o.name, o.world_mesh.get(), o.color, o.inside_color};
      node.materials = o.materials;
      node.inside_material = inside_material(o);
      // An undeformed object loaded from a file of several nodes writes the file's node tree back (write_glb checks
      // that the parts still cover its rest mesh exactly).
      if (!o.parts.empty() && !o.ffd && !o.dffd && !o.clip && !o.morph) {
        node.parts = &o.parts;
        node.rest_mesh = o.rest_mesh.get();
        node.object_to_world = o.transform.matrix();
      }
      out.nodes.push_back(node);
    }
    for (const auto& layer : o.ddm_layers) {
      if (!layer->mesh) continue;
      auto world = std::make_shared<const TriMesh>(ddm_layer_world_mesh(o, *layer, *layer->mesh, 0.0));
      GltfNode node{o.name + "/" + layer->name, world.get(), layer->color.value_or(o.color), o.inside_color};
      // Texture-mapped tiles (seed Fig. 5.12); plain ones among them in the layer's colour.
      node.materials = ddm_tile_materials(layer->tiles, glm::dvec3(node.color)).set;
      out.nodes.push_back(node);
      out.owned.push_back(std::move(world));
    }
  }
  for (const VolumeObject& v : scene.volumes()) {
    if (!v.render_visible) continue;
    if (v.iso_mesh) out.nodes.push_back({v.name + "/iso", v.iso_mesh.get(), v.color, v.color});
    if (!v.silhouette.enabled) continue;
    // The silhouettes of the scene's current camera (extracted again when the stored ones are for another view),
    // every level's: "<volume>/silhouettes", then "<volume>/silhouettes.<k>" in the further level's colour.
    const bool stored = v.silhouettes && same_view(v.silhouette_camera, scene.camera);
    SilhouetteParams params = v.silhouette.params;
    params.hidden_test = v.silhouette.hidden != "show";
    auto level_node = [&](std::shared_ptr<const SilhouetteResult> sil, double iso, std::string name, glm::vec3 color) {
      if (!sil || !stored)
        sil = std::make_shared<const SilhouetteResult>(
            extract_silhouettes(*v.spline, *v.table, iso, v.silhouette_view(scene.camera), params));
      auto strips = std::make_shared<const std::vector<std::vector<glm::vec3>>>(
          silhouette_line_strips(sil->polylines, v.silhouette.hidden != "remove"));
      GltfNode node;
      node.name = std::move(name);
      node.color = color;
      node.line_strips = strips.get();
      out.nodes.push_back(node);
      out.owned_strips.push_back(std::move(strips));
    };
    level_node(v.silhouettes, v.iso, v.name + "/silhouettes", glm::vec3(0.0f));
    for (std::size_t k = 0; k < v.more_levels.size(); ++k)
      level_node(v.more_levels[k].silhouettes, v.more_levels[k].iso, v.name + "/silhouettes." + std::to_string(k + 1),
                 glm::convertSRGBToLinear(v.more_levels[k].color));
  }
  return out;
}

Scene render_visible_scene(const Scene& scene) {
  Scene out = scene;
  for (const SceneObject& o : scene.objects()) {
    if (!o.render_visible)
      out.remove(o.name);
    else if (!o.visible)
      out.find(o.name)->visible = true;
  }
  for (const VolumeObject& v : scene.volumes()) {
    if (!v.render_visible) {
      out.remove_volume(v.name);
    } else if (!v.visible) {
      VolumeObject shown = v;
      shown.visible = true;
      out.replace_volume(std::move(shown));
    }
  }
  return out;
}

}  // namespace trispline::core
