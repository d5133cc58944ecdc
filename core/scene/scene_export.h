// trispline::core scene export — the meshes scene.glb and animation.glb hold: every object's world mesh (with its
// materials; an undeformed object with parts as its file's node tree, GltfNode::parts), then every
// tile layer that is not baked (DDM, seed ch. 5) as a node of its own named "<object>/<layer>", in world units (the
// object's transform applied; layers follow their object's visibility); then per volume its iso-surface mesh when
// extracted ("<volume>/iso") and, when its silhouettes are enabled, the silhouettes of the scene camera as glTF line
// strips ("<volume>/silhouettes", world millimetres; hidden parts left out when the volume's hidden mode is remove).
#pragma once

#include <memory>
#include <vector>

#include "core/mesh/gltf_io.h"
#include "core/scene/scene.h"

namespace trispline::core {

struct SceneExport {
  std::vector<GltfNode> nodes;                        // in scene order; each object followed by its layers
  std::vector<std::shared_ptr<const TriMesh>> owned;  // keeps the layers' world meshes alive for `nodes`
  std::vector<std::shared_ptr<const std::vector<std::vector<glm::vec3>>>> owned_strips;  // volumes' silhouette strips
};

// Objects without a world mesh and objects and volumes out of renders (render_visible false) are left out. Throws
// std::invalid_argument from transformed() on a degenerate transform.
SceneExport scene_export_nodes(const Scene& scene);

// Copy of `scene` as renders show it (recordings, farm frames, headless images): only the objects and volumes whose
// render_visible is set, each with visible = true (hide_render decides, hide_viewport does not, as in Blender). Meshes,
// splines and tables are shared; a volume left out costs nothing afterwards (no ray casting, no silhouettes).
Scene render_visible_scene(const Scene& scene);

}  // namespace trispline::core
