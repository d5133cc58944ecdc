// Internal to trispline_mesh: reading OBJ, PLY, OFF, STL, Collada and FBX through assimp (the Open Asset Import
// Library).
//
//   read_assimp_file   a path → checked (file_check, mesh_precheck), read once, parsed: mesh, materials, parts
//   read_assimp_mesh   the file's bytes (already checked by mesh_precheck) → one TriMesh, every face of every mesh
//
// What becomes of a file's elements:
//   * polygons of 3+ corners are triangulated by assimp (aiProcess_Triangulate: ear clipping, so concave polygons
//     keep their shape); every one of them is kept, degenerate ones included, so #T is the file's face count after
//     triangulation — the count `assimp info FILE` prints.
//   * point and line elements are not surface: they are counted in MeshLoadReport and left out; a file holding
//     nothing else is refused ("no faces").
//   * meshes are placed by their node's world transform and joined into one TriMesh; vertices equal in every
//     attribute the file gives (position, and normal and uv where present) are welded, so an OBJ's groups, a PLY's
//     per-corner copies and an STL's unshared corners become one connected mesh, in order of first use. STL face
//     normals are dropped (they are per face, not per vertex); normals missing from any mesh are computed later for
//     the whole mesh.
//   * Collada and FBX files of more than one mesh node become parts (MeshPart, one per node, in depth-first node
//     order; a node's meshes — assimp splits a mesh by material — are one part): vertices are welded within a part
//     only, so each part's vertices and triangles are one contiguous range. OBJ objects and groups stay one welded
//     mesh without parts (an OBJ has no node transforms, and its groups share vertices).
//   * uvs are flipped to glTF's convention (v → 1 − v, aiProcess_FlipUVs; see model_load.h).
//   * with materials: every face keeps its mesh's material slot (face_material), the scene's materials become a
//     MaterialSet (assimp_material.h); the OBJ's `mtllib` files are served to assimp from the model's folder only,
//     checked and rewritten first (check_mtl_text), never the model itself under another name.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// .obj .ply .off .stl .dae .fbx
bool is_assimp_extension(const std::string& ext);

struct AssimpModel {
  TriMesh mesh;                                  // face_material filled only with materials
  std::shared_ptr<const MaterialSet> materials;  // null without materials or when the file has none
  std::vector<MeshPart> parts;                   // Collada / FBX files of several mesh nodes
  std::vector<std::string> warnings;             // material libraries that could not be read
};

// The whole assimp load of `path` (extension `ext`, lower case): check_input_file, precheck_mesh_head on the head,
// read_input_file, prepare_mesh_bytes, precheck_mesh_file, then read_assimp_mesh; `materials` also reads the MTL
// files (from the model's folder) and texture images. Loose points and lines are refused unless
// options.ignore_loose. Throws MeshIoError naming `path`.
AssimpModel read_assimp_file(const std::filesystem::path& path, const std::string& ext, const MeshLoadOptions& options,
                             MeshLoadReport& report, bool materials);

// `bytes` is the whole file, `ext` its lower-case extension (".obj" .ply .off .stl .dae .fbx). Throws MeshIoError
// naming `path` when assimp refuses the file or it holds no triangle. Without `materials` no other file is opened
// (an OBJ's mtllib lines were made comments by prepare_mesh_bytes); with them, `mtllibs` are the OBJ's material
// libraries (prepare_mesh_bytes collected them), read from its folder, and the textures are read (see above).
AssimpModel read_assimp_mesh(const std::filesystem::path& path, const std::string& ext,
                             const std::vector<unsigned char>& bytes, MeshLoadReport& report, bool materials,
                             const std::vector<std::string>* mtllibs = nullptr);

}  // namespace trispline::core
