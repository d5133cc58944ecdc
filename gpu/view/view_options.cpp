#include "gpu/view/view_options.h"

#include "core/scene/scene.h"

namespace trispline::gpu {

const std::shared_ptr<const core::TriMesh>* Overlays::mesh_for(const std::string& object) const {
  for (const MeshInPlace& m : meshes)
    if (m.object == object) return m.mesh ? &m.mesh : nullptr;
  return nullptr;
}

const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>* Overlays::lattice_for(
    const std::string& object) const {
  for (const LatticeInPlace& l : lattices_in_place)
    if (l.object == object) return l.lattice ? &l.lattice : nullptr;
  return nullptr;
}

const VolumeInPlace* Overlays::volume_for(const std::string& volume) const {
  for (const VolumeInPlace& v : volumes_in_place)
    if (v.volume == volume) return &v;
  return nullptr;
}

bool material_shading(const core::Scene& scene, Shading shading) {
  if (shading != Shading::automatic) return shading == Shading::material;
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible) continue;
    if ((o.materials && o.materials->has_textures()) || o.inside_textured()) return true;
    for (const auto& layer : o.ddm_layers)  // texture-mapped tiles
      if (layer)
        for (const core::DdmTile& t : layer->tiles)
          if (t.materials && t.materials->has_textures()) return true;
  }
  return false;
}

ScreenStroke& ViewOptions::add_stroke(std::vector<glm::dvec2> px) {
  return overlays.strokes.emplace_back(ScreenStroke{std::move(px), style.stroke_color, style.stroke_width_px});
}

}  // namespace trispline::gpu
