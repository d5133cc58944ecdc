// trispline::core mesh files — loading and saving TriMesh, plus the checks every loaded mesh goes through.
//
//   load_mesh               OBJ, PLY, OFF, STL (OpenMesh) and glTF 2.0 .gltf/.glb (tinygltf) → TriMesh
//   save_mesh               TriMesh → OBJ or PLY (OpenMesh)
//   validate_mesh           finite positions, non-empty, indices in range; throws MeshIoError
//   compute_vertex_normals  area-weighted vertex normals
//   mesh_bounds             axis-aligned bounds of the positions
//
// Errors: every function here reports bad input by throwing MeshIoError (a std::runtime_error) whose message names
// the file (or `what`) and the reason: "file not found", "unsupported extension", "cannot parse",
// "non-finite vertex coordinate", "empty mesh", "index out of range".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Loads a triangle mesh, units as in the file.
//   .obj .ply .off .stl  through OpenMesh into a polygon mesh, polygons split into fans (v0, vi, vi+1); vertex order
//                        is the file's (STL, which has no shared vertices, gets OpenMesh's merged vertices in order
//                        of first use). Normals and texture coordinates are kept when the file has them per vertex.
//   .gltf .glb           every TRIANGLES primitive of every node of the default scene (all root nodes of all scenes
//                        if none is marked default; all meshes untransformed if there are no nodes), each with its
//                        node's world transform; POSITION, NORMAL, TEXCOORD_0; indices of any unsigned type.
// Missing normals are computed (compute_vertex_normals). Result passes validate_mesh.
// Throws MeshIoError (see header comment).
TriMesh load_mesh(const std::filesystem::path& path);

// Writes .obj or .ply (ASCII for OBJ, binary little-endian for PLY) through OpenMesh, with normals when present and
// texture coordinates when present. Throws MeshIoError on an unsupported extension or a failed write.
void save_mesh(const std::filesystem::path& path, const TriMesh& mesh);

// Throws MeshIoError "<what>: ..." if the mesh has no vertices or no triangles, a non-finite position, an index
// >= #V, or normals/uvs whose count is neither 0 nor #V.
void validate_mesh(const TriMesh& mesh, const std::string& what);

// Replaces mesh.normals by area-weighted vertex normals (sum of unnormalised face normals (b−a)×(c−a), then
// normalised). Vertices with no non-degenerate incident triangle get (0,1,0).
void compute_vertex_normals(TriMesh& mesh);

// Bounds of mesh.positions (invalid box if there are none).
Aabb mesh_bounds(const TriMesh& mesh);

// Signed volume enclosed by the triangles, world units³ (Σ a·(b×c)/6); > 0 for a closed mesh wound CCW seen from
// outside.
double signed_volume(const TriMesh& mesh);

// Lower-case extension with the dot, e.g. ".glb".
std::string lower_extension(const std::filesystem::path& path);

}  // namespace trispline::core
