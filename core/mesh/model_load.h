// trispline::core model files — a mesh file with what an artist sees on it: its materials, textures and parts.
//
//   LoadedModel  the mesh (as load_mesh), the file's materials with their decoded images, its parts (nodes)
//   load_model   path → LoadedModel, whole or refused (MeshIoError); a texture that cannot be read is not a refusal
//
// load_mesh (mesh_io.h) is load_model without materials: the same triangles, vertices and order, no texture read.
// Formats and what becomes of their materials:
//   .obj + .mtl          Kd → base colour, map_Kd → base colour texture, d / Tr → alpha (BLEND below 1), map_d →
//                        alpha (MASK, cutoff 0.5), bump / map_Bump / norm → normal texture (scale = -bm), Ke / map_Ke
//                        → emissive, Ns → roughness (Blender's estimate 1 − √(Ns/1000)), Pr / Pm when given; the MTL
//                        files named by `mtllib` are read only from the OBJ's folder or below (see assimp_io.h)
//   .dae .fbx            (assimp) the same mapping from the file's Phong/Lambert or PBR values; parts per mesh node
//   .ply .off .stl       no materials (one slot, the object colour)
//   .gltf .glb           (tinygltf) glTF 2.0 materials as written
// UVs (TriMesh::uvs) follow glTF 2.0 §3.7.2.1: (0,0) is the top-left corner of the image, v grows downwards. Formats
// with v growing upwards (OBJ, PLY, Collada, FBX) are flipped on reading (v → 1 − v) and on writing (save_mesh).
// Textures are read from the model's folder or below (symlinks and ".." resolved first): a path outside it, a missing
// file, one over kMaxModelTextureFileBytes or one OpenImageIO cannot decode leaves the material without that image's
// pixels and names the file and the reason in MaterialImage::error (the object still loads).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Largest texture file a model may refer to, bytes.
inline constexpr std::uintmax_t kMaxModelTextureFileBytes = std::uintmax_t(256) << 20;

struct LoadedModel {
  TriMesh mesh;                                  // as load_mesh; face_material indexes materials->materials
  std::shared_ptr<const MaterialSet> materials;  // null when the file has no material
  std::vector<MeshPart> parts;                   // the file's mesh nodes when it has several; empty otherwise
  std::vector<std::string> warnings;             // side files left out: "material library 'x.mtl': file not found …"
  // Images that could not be read, "<uri>: <why>", in image order (also in materials->images[i]->error).
  std::vector<std::string> texture_errors() const;
};

// Loads `path` as load_mesh does (same checks, same refusals), with its materials and their images decoded
// (OpenImageIO) and, for files of several mesh nodes, its parts. Throws MeshIoError as load_mesh.
LoadedModel load_model(const std::filesystem::path& path, const MeshLoadOptions& options = {},
                       MeshLoadReport* report = nullptr);

// Removes repeated triangles (remove_duplicate_triangles) keeping `parts`' triangle ranges consistent, checks the
// mesh (validate_mesh), makes part names unique (Blender's ".001" suffixes; an unnamed part is "part") and computes
// missing normals: what every loader does last. Returns the number removed.
std::size_t finish_loaded_mesh(TriMesh& mesh, std::vector<MeshPart>& parts, const std::string& what);

// The bytes of the file `relative` names (as written in the model: '/' or '\' separators) under the folder of
// `model`: after resolving ".." and symlinks it must lie in that folder or below, and be a regular file of at most
// `max_bytes`. Throws MeshIoError "'x.png': resolves to '/a/x.png', outside the folder '/a/b' of the model" /
// "'x.png': file not found" / "'/etc/x': is an absolute path …" (without the model's name: callers keep it as an
// image error).
std::vector<unsigned char> read_model_side_file(const std::filesystem::path& model, const std::string& relative,
                                                std::uintmax_t max_bytes);

}  // namespace trispline::core
