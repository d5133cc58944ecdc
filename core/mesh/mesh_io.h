// trispline::core mesh files — loading and saving TriMesh, plus the checks every loaded mesh goes through.
//
//   load_mesh               OBJ, PLY, OFF, STL, Collada, FBX (assimp) and glTF 2.0 .gltf/.glb (tinygltf) → TriMesh,
//                           whole or refused (model_load.h: the same with materials and parts)
//   save_mesh               TriMesh → OBJ or PLY (OpenMesh)
//   validate_mesh           finite positions, non-empty, indices in range; throws MeshIoError
//   compute_vertex_normals  area-weighted vertex normals
//
// Errors: every function here reports bad input by throwing MeshIoError (a std::runtime_error) whose message names
// the file (or `what`) and the reason: "file not found", "unsupported extension", "cannot parse",
// "non-finite vertex coordinate", "empty mesh", "index out of range".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/base/text.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

class MeshIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a load met besides the triangles it returns.
struct MeshLoadReport {
  std::size_t faces = 0;            // triangles loaded (#T), after triangulating the file's polygons
  std::size_t ignored_points = 0;   // point elements left out (only with MeshLoadOptions::ignore_loose)
  std::size_t ignored_lines = 0;    // line elements left out (only with MeshLoadOptions::ignore_loose)
  std::size_t duplicate_faces = 0;  // repeated triangles removed (remove_duplicate_triangles); faces excludes them
  std::string loader;               // "assimp" or "tinygltf"
};

struct MeshLoadOptions {
  // false (default): a file holding point or line elements besides its faces is refused, naming their counts, so
  // nothing of a file is dropped silently; true: they are left out and counted in MeshLoadReport.
  bool ignore_loose = false;
};

// Loads a triangle mesh, units as in the file: all of it, or nothing (MeshIoError).
// Before any parser runs, the path must be a regular file (not a directory, FIFO or device) of at most
// kMaxMeshFileBytes, and the file must pass mesh_precheck's size/header checks against kMeshLoadMemoryBudget.
//   .obj .ply .off .stl .dae .fbx
//                        through assimp (aiProcess_Triangulate: polygons ear-clipped into #faces − 2 triangles each);
//                        meshes joined, vertices equal in every attribute welded, in order of first use (see
//                        core/mesh/assimp_io.h). Normals and texture coordinates are kept when every mesh has them
//                        per vertex (STL normals are per face and dropped); uvs flipped to glTF's v-down convention
//                        (model_load.h). Collada and FBX meshes are placed by their node transforms. 4-D OFF, binary
//                        OFF, files with no faces, 2-corner OBJ faces and truncated OBJ vertex lines are refused.
//   .gltf .glb           every TRIANGLES primitive of every node of the default scene (all root nodes of all scenes
//                        if none is marked default; all meshes untransformed if there are no nodes), each with its
//                        node's world transform; POSITION, NORMAL, TEXCOORD_0; indices of any unsigned type.
// A triangle that repeats an earlier one (same vertices, same orientation) is removed and counted in
// MeshLoadReport::duplicate_faces: it adds no surface, only a non-manifold edge (see remove_duplicate_triangles).
// Missing normals are computed (compute_vertex_normals). Result passes validate_mesh.
// Throws MeshIoError (see header comment).
TriMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options = {},
                  MeshLoadReport* report = nullptr);

// Writes .obj or .ply (ASCII for OBJ, binary little-endian for PLY) through OpenMesh, with normals when present and
// texture coordinates when present (v flipped back to the formats' v-up convention). Throws MeshIoError on an
// unsupported extension or a failed write.
void save_mesh(const std::filesystem::path& path, const TriMesh& mesh);

// Throws MeshIoError "<what>: ..." if the mesh has no vertices or no triangles, a non-finite position, an index
// >= #V, or normals/uvs whose count is neither 0 nor #V.
void validate_mesh(const TriMesh& mesh, const std::string& what);

// Removes every triangle whose vertex indices repeat an earlier triangle's up to rotation — (a,b,c), (b,c,a) and
// (c,a,b) are the same face; the reversed (a,c,b) is the other side and is kept. The first copy stays, the order
// of the others is kept, face_material follows. Vertices are not touched. Returns how many were removed.
// (Blender's Mesh.validate removes such faces on import too.)
std::size_t remove_duplicate_triangles(TriMesh& mesh);

// Replaces mesh.normals by area-weighted vertex normals (sum of unnormalised face normals (b−a)×(c−a), then
// normalised). Vertices with no non-degenerate incident triangle get (0,1,0).
void compute_vertex_normals(TriMesh& mesh);

// Signed volume enclosed by the triangles, world units³ (Σ a·(b×c)/6); > 0 for a closed mesh wound CCW seen from
// outside.
double signed_volume(const TriMesh& mesh);

}  // namespace trispline::core
