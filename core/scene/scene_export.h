// trispline::core scene export — the meshes scene.glb and animation.glb hold: every object's world mesh, then every
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

// Objects without a world mesh are left out. Throws std::invalid_argument from transformed() on a degenerate
// transform.
SceneExport scene_export_nodes(const Scene& scene);

}  // namespace trispline::core
