// Internal to trispline_mesh: reading OBJ, PLY, OFF and STL through assimp (the Open Asset Import Library).
//
//   read_assimp_mesh   the file's bytes (already checked by mesh_precheck) → one TriMesh, every face of every mesh
//
// What becomes of a file's elements:
//   * polygons of 3+ corners are triangulated by assimp (aiProcess_Triangulate: ear clipping, so concave polygons
//     keep their shape); every one of them is kept, degenerate ones included, so #T is the file's face count after
//     triangulation — the count `assimp info FILE` prints.
//   * point and line elements are not surface: they are counted in MeshLoadReport and left out; a file holding
//     nothing else is refused ("no faces").
//   * meshes are placed by their node's world transform (identity for these formats) and joined into one TriMesh;
//     vertices equal in every attribute the file gives (position, and normal and uv where present) are welded, so
//     an OBJ's groups, a PLY's per-corner copies and an STL's unshared corners become one connected mesh, in order
//     of first use. STL face normals are dropped (they are per face, not per vertex); normals missing from any mesh
//     are computed later for the whole mesh.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/mesh/mesh_io.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// `bytes` is the whole file, `ext` its lower-case extension (".obj" .ply .off .stl). Throws MeshIoError
// naming `path` when assimp refuses the file or it holds no triangle. No other file is opened (an OBJ's mtllib is
// not followed: materials are not used).
TriMesh read_assimp_mesh(const std::filesystem::path& path, const std::string& ext,
                         const std::vector<unsigned char>& bytes, MeshLoadReport& report);

}  // namespace trispline::core
