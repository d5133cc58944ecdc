// Internal helpers shared by the tinygltf-based files of core/mesh (gltf_io, gltf_anim_io, mesh_clip); not part of
// the public API. Include <tiny_gltf.h> the way gltf_io.cpp explains (Debian's build defaults, no macros).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace trispline::core::gltf_model {

// The node roots load_mesh walks: the default scene's, else every scene's in order, else (no scene at all) every
// node that is nobody's child. Out-of-range child indices are ignored here (the traversal rejects them).
std::vector<int> root_nodes(const tinygltf::Model& model);

// Appends raw bytes to buffer 0 (padded to 4-byte alignment first) as a new buffer view; returns its index.
// target: GL buffer target (e.g. TINYGLTF_TARGET_ARRAY_BUFFER) or 0 for none.
int add_view(tinygltf::Model& model, const void* data, std::size_t bytes, int target);

// Appends `idx` (vertex indices, 3 per triangle) as a new element-array view and an unsigned-int scalar accessor over
// it; returns the accessor's index (a primitive's `indices`).
int add_index_accessor(tinygltf::Model& model, const std::vector<std::uint32_t>& idx);

// Appends the project's material (PBR base colour `rgb` in linear [0,1], metallic 0, roughness 0.6, double-sided)
// named `name`; returns its index.
int add_material(tinygltf::Model& model, const std::string& name, const glm::vec3& rgb);

// Writes `model` as a binary glTF to "<path>.tmp", then renames it over `path` (atomic on one file system). An empty
// first buffer is dropped (glTF forbids empty buffers). Throws MeshIoError naming the file.
void write_glb_atomically(tinygltf::Model& model, const std::filesystem::path& path);

}  // namespace trispline::core::gltf_model
