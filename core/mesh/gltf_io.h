// trispline::core glTF 2.0 export and import (tinygltf).
//
//   write_glb           the scene export (scene.glb): one node + mesh + material per object, named by the object id
//                       (a second primitive + "<id>.inside" material for the inside faces, TriMesh::face_material);
//                       line drawings (silhouettes) as LINE_STRIP primitives
//   read_gltf_objects   the reverse, one object per mesh-carrying node; also the glTF path of load_mesh
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct GltfNode {
  std::string name;                             // node and mesh name (the object id)
  const TriMesh* mesh = nullptr;                // world units; null or empty → a node with no mesh
  glm::vec3 color{0.8f};                        // linear RGB in [0,1], the PBR base colour (metallic 0, roughness 0.6)
  glm::vec3 inside_color{0.62f, 0.10f, 0.08f};  // linear RGB of the mesh's kMaterialInside faces (cut surfaces)
  // Polylines to draw as lines (silhouettes), world units: #S strips of #P_s points; null or empty → none.
  const std::vector<std::vector<glm::vec3>>* line_strips = nullptr;
};

// Writes a binary glTF (.glb): per node one mesh with one TRIANGLES primitive, float32 POSITION (with min/max),
// NORMAL and TEXCOORD_0 when the mesh has them, uint32 indices, vertices in the mesh's order, and one material
// named by the node. A mesh with kMaterialInside faces (TriMesh::face_material) gets two primitives sharing the
// vertex accessors: its surface faces (material "<name>", `color`; left out when there are none) and its inside
// faces (material "<name>.inside", `inside_color`), each in face order. A mesh without inside faces is written
// exactly as before.
// A node's line_strips add one LINE_STRIP primitive (mode 3) per strip of ≥ 2 points (shorter ones draw nothing and
// are left out), after the triangle primitives of its mesh (a node without a mesh gets a mesh of lines only): float32
// POSITION with min/max, no indices, all sharing one unlit material (KHR_materials_unlit) of the node's `color`,
// named "<name>" — "<name>.lines" when the node also has triangles. Nodes without line strips are written exactly as
// before.
// Written to "<path>.tmp" then renamed over `path` (atomic on one file system).
// Throws MeshIoError if a mesh fails validate_mesh, a line strip holds a non-finite point, or the file cannot be
// written.
void write_glb(const std::filesystem::path& path, const std::vector<GltfNode>& nodes);

struct GltfObject {
  std::string name;       // node name, or the mesh name if the node has none
  TriMesh mesh;           // positions/normals in world space (node transforms applied); normals empty if absent
  glm::vec3 color{0.8f};  // base colour of the first primitive's material (0.8 grey if none)
  glm::vec3 inside_color{0.62f, 0.10f, 0.08f};  // base colour of a "*.inside" material (see read_gltf_objects)
};

// Reads a .gltf or .glb: one object per node that has a mesh with triangles (a points- or lines-only mesh, such as a
// volume's silhouettes, is left out), in depth-first node order from the scene's roots
// (see load_mesh for which roots), all TRIANGLES primitives of that mesh concatenated; a "*.inside" primitive that
// uses the same vertex accessors as an earlier primitive of the mesh shares its vertices (as write_glb writes it).
// When a primitive's material name ends in ".inside", face_material is filled: kMaterialInside for that
// primitive's triangles, kMaterialSurface for the others (and color comes from the first other primitive).
// Objects are not validated.
// Throws MeshIoError on a missing or unparseable file, a non-float attribute, or a non-TRIANGLES primitive only
// model.
std::vector<GltfObject> read_gltf_objects(const std::filesystem::path& path);

}  // namespace trispline::core
