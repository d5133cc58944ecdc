// trispline::core glTF 2.0 export and import (tinygltf).
//
//   write_glb           the scene export (scene.glb): one node + mesh + material per object, named by the object id
//                       (a second primitive + "<id>.inside" material for the inside faces, TriMesh::face_material);
//                       line drawings (silhouettes) as LINE_STRIP primitives
//   read_gltf_file      the reverse, one object per mesh-carrying node, with the file's materials and images; also
//                       the glTF path of load_mesh (read_gltf_objects: the objects alone)
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct GltfNode {
  std::string name;                             // node and mesh name (the object id)
  const TriMesh* mesh = nullptr;                // world units; null or empty → a node with no mesh
  glm::vec3 color{0.8f};                        // linear RGB in [0,1], the PBR base colour (metallic 0, roughness 0.6)
  glm::vec3 inside_color{0.62f, 0.10f, 0.08f};  // linear RGB of the mesh's kMaterialInside faces (cut surfaces)
  // Polylines to draw as lines (silhouettes), world units: #S strips of #P_s points; null or empty → none.
  const std::vector<std::vector<glm::vec3>>* line_strips = nullptr;
  // The object's materials (TriMesh::face_material indexes them); null or empty → `color`, as above.
  std::shared_ptr<const MaterialSet> materials = nullptr;
  // The material of the kMaterialInside faces (a textured inside, core::inside_material: its first material, with its
  // texture); null or empty → "<name>.inside" of `inside_color`.
  std::shared_ptr<const MaterialSet> inside_material = nullptr;
  // The file's node tree of an undeformed loaded object (SceneObject::parts over `rest_mesh`, object space, placed by
  // `object_to_world`); null or empty → one node of `mesh`.
  const std::vector<MeshPart>* parts = nullptr;
  const TriMesh* rest_mesh = nullptr;
  glm::dmat4 object_to_world{1.0};
};

// Writes a binary glTF (.glb): per node one mesh with one TRIANGLES primitive, float32 POSITION (with min/max),
// NORMAL and TEXCOORD_0 when the mesh has them, uint32 indices, vertices in the mesh's order, and one material
// named by the node. A mesh with kMaterialInside faces (TriMesh::face_material) gets two primitives sharing the
// vertex accessors: its surface faces (material "<name>", `color`; left out when there are none) and its inside
// faces (material "<name>.inside", `inside_color`, or `inside_material` with its texture), each in face order. A mesh
// without inside faces is written exactly as before.
// A node with `materials` gets instead one primitive per material slot its faces use, in the order of their first
// faces (faces of a slot past the set's end use a "<name>" material of `color`), then the inside primitive: with one
// slot all share the vertex accessors, with several each primitive holds the vertices its faces use, in vertex order
// (as glTF exporters write per-material primitives; read back, a file's vertex order returns). The set's materials
// are written with their textures, samplers and images: buffer views holding the source bytes when PNG or JPEG, else
// PNG re-encoded from the decoded pixels (material_image.h gltf_image_bytes); an unreadable image is left out with
// its textures. A set, an image or a sampler shared by several nodes is written once.
// A node with `parts` and a `rest_mesh` they cover exactly (in order; instances of one mesh_index of equal counts) is
// written as a node "<name>" of matrix `object_to_world` (the node first, its children after it), whose children are
// the parts, "<name>/<part name>" ("<name>/<mesh index>" for an unnamed part), of matrix MeshPart::world; parts of
// one mesh_index share one glTF mesh (instances), made of the vertices of the best-conditioned instance (largest
// |det|) brought back by the inverse of its matrix.
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
  int mesh_index = -1;    // the file's mesh the node draws
  glm::dmat4 world{1.0};  // the node's world transform (already applied to `mesh`)
  TriMesh mesh;           // positions/normals in world space (node transforms applied); normals empty if absent
  glm::vec3 color{0.8f};  // base colour of the first primitive's material (0.8 grey if none)
  glm::vec3 inside_color{0.62f, 0.10f, 0.08f};  // base colour of a "*.inside" material (see read_gltf_objects)
};

// Reads a .gltf or .glb: one object per node that has a mesh with triangles (a points- or lines-only mesh, such as a
// volume's silhouettes, is left out), in depth-first node order from the scene's roots
// (see load_mesh for which roots), all TRIANGLES primitives of that mesh concatenated; a "*.inside" primitive that
// uses the same vertex accessors as an earlier primitive of the mesh shares its vertices (as write_glb writes it).
// face_material holds per triangle its primitive's slot in GltfFile::materials (left empty when all are 0): a primitive
// whose material name ends in ".inside" gets kMaterialInside (write_glb's cut surfaces), a primitive without a
// material the glTF default material (appended to the set). color comes from the first other primitive's material.
// Objects are not validated.
// Throws MeshIoError on a missing or unparseable file, a non-float attribute, or a non-TRIANGLES primitive only
// model.
std::vector<GltfObject> read_gltf_objects(const std::filesystem::path& path);

struct GltfFile {
  std::vector<GltfObject> objects;
  // The file's materials (gltf_materials: all but "*.inside" ones, then the default material if a primitive has
  // none), images decoded; null when the file names no material (face_material then holds only inside faces).
  std::shared_ptr<const MaterialSet> materials = nullptr;
  std::vector<std::string> warnings;  // unreadable images, e.g. "image 0 ('bark.jpg'): … file not found"
};

// read_gltf_objects with the file's materials (`materials` false: none read, no image opened; face_material as
// read_gltf_objects: kMaterialInside or kMaterialSurface). An image that cannot be read or decoded (missing file, URI
// outside the file's folder, bad bytes, over the size limits) does not fail the load: the image keeps `error` and a
// warning says which and why. Throws as read_gltf_objects, and MeshIoError for texture / image / sampler indices out of
// range.
GltfFile read_gltf_file(const std::filesystem::path& path, bool materials = true);

// A glTF file as one object: the objects of read_gltf_file concatenated in load order (vertices, triangles and
// face_material; normals kept when every node has them, uvs when any has: (0,0) for the others), one MeshPart per
// mesh node when there are at least two. UVs are TEXCOORD_0 as written (glTF 2.0 §3.7.2.1: (0,0) is the image's
// top-left corner, v grows downwards), the convention of TriMesh::uvs. Not validated; throws as read_gltf_file.
struct GltfModel {
  TriMesh mesh;
  std::shared_ptr<const MaterialSet> materials;  // null when the file names no material
  std::vector<MeshPart> parts;                   // empty for a file of one mesh node
  std::vector<std::string> warnings;             // unreadable images (read_gltf_file)
};
GltfModel read_gltf_model(const std::filesystem::path& path);

}  // namespace trispline::core
