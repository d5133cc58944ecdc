// Internal to core/mesh: glTF 2.0 materials ↔ MaterialSet (core/mesh/material.h), through tinygltf.
//
//   read_gltf_materials   a checked tinygltf::Model (gltf_read::read_model) → its materials, textures, samplers and
//                         images, images decoded by OpenImageIO (material_image.h)
//   GltfMaterialWriter    appends MaterialSets to a model being written, images embedded as buffer views, each set
//                         and each image written once per file
// Include <tiny_gltf.h> the way gltf_io.cpp explains (Debian's build defaults, no macros).
#pragma once

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"

namespace trispline::core::gltf_materials {

// Σ decoded bytes (rgba8) of the images of one file: 1.5 GiB, half of kMeshLoadMemoryBudget.
inline constexpr std::uint64_t kMaxFileImageBytes = std::uint64_t(3) << 29;

struct ReadMaterials {
  MaterialSet set;                    // the file's materials in file order, except "*.inside" ones (write_glb's cuts)
  std::vector<int> slot;              // glTF material index → index into set.materials, -1 for a "*.inside" material
  std::vector<std::string> warnings;  // per unreadable image: "image 0 ('bark.jpg'): file not found"
};

// Every material of `model` (glTF 2.0 §5.19): factors, textures with their texCoord and sampler (§5.26), normal scale,
// occlusion strength, emissive, alpha mode and cutoff, double sided. Images used by a texture are read (data: URI,
// buffer view, or an external file under the buffer folder rule: gltf_read::external_image_bytes) and decoded; an
// image that cannot be read or decoded, or would pass kMaxFileImageBytes decoded, keeps its uri and an `error` (and
// a warning) and the materials still load. Throws MeshIoError naming `path` for a texture, image or sampler index
// out of range, or more than kMaxMaterialsPerMesh materials.
ReadMaterials read_gltf_materials(const tinygltf::Model& model, const std::filesystem::path& path);

// The glTF 2.0 default material (§3.9.6: base colour 1, metallic 1, roughness 1), for primitives without one.
Material default_material();

// Writes MaterialSets into one model. Images go into buffer 0 as buffer views: their source bytes when PNG or JPEG,
// else PNG re-encoded from rgba8 (gltf_image_bytes); unreadable images are left out with the textures that use
// them. Equal samplers are written once.
class GltfMaterialWriter {
 public:
  explicit GltfMaterialWriter(tinygltf::Model& model) : model_(model) {}
  // glTF material index of each of `set`'s materials (written on first use of `set`).
  const std::vector<int>& materials(const std::shared_ptr<const MaterialSet>& set);

 private:
  int texture(const MaterialSet& set, const MaterialTexture& t);  // -1 when absent or unreadable
  int image(const std::shared_ptr<const MaterialImage>& image);   // -1 when unreadable
  int sampler(const TextureSampler& s);

  tinygltf::Model& model_;
  std::map<const MaterialSet*, std::vector<int>> sets_;
  std::vector<std::shared_ptr<const MaterialSet>> keep_;  // the sets_ keys stay valid while writing
  std::map<const MaterialImage*, int> images_;
  std::vector<std::pair<TextureSampler, int>> samplers_;
  std::map<std::pair<int, int>, int> textures_;  // (image, sampler) → texture
};

}  // namespace trispline::core::gltf_materials
