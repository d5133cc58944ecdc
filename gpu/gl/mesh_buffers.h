// trispline::gpu::MeshBuffers — one triangle mesh on the GPU: a VAO over separate, tightly packed float32
// buffers (positions #V×3, normals #V×3, texture coordinates #V×2) and a uint32 index buffer (#F×3).
//
// Layout contract (shared with the GLSL FFD evaluator): attribute 0 = position (vec3), attribute 1 =
// normal (vec3), attribute 2 is reserved for per-vertex parameters (u,v,w), attribute 3 = texture coordinate (vec2;
// a constant (0,0) when the mesh has no TriMesh::uvs). The position and normal buffers are
// plain `float[]` arrays, so a compute shader can bind them as SSBOs (std430 `float p[]`, index 3·i + c) and
// write deformed vertices in place, with no CPU round trip; the renderer then draws them unchanged.
//
// Materials: the index buffer holds the triangles ordered by TriMesh::face_material (a stable sort by slot: slot 0,
// 1, … and kMaterialInside — DFFD caps, incision walls — last, each group in mesh order), so the renderer draws one
// range per material (Material shading) or the surface and inside ranges with two colours (Solid). Vertex order is
// never changed (update_vertices and the FFD evaluators write vertices by their mesh index); deformations move
// positions and normals while the texture coordinates ride along. With one slot the index buffer is the mesh's.
#pragma once

#include <cstddef>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "gpu/gl/gl_resource.h"

namespace trispline::gpu {

// A contiguous run of triangles in the index buffer: triangles [first, first + count).
struct TriangleRange {
  std::size_t first = 0;
  std::size_t count = 0;
};

// The triangles of one material slot (TriMesh::face_material value) in the index buffer.
struct MaterialRange {
  core::MaterialSlot slot = 0;
  TriangleRange range;
};

class MeshBuffers {
 public:
  MeshBuffers() = default;  // empty; call upload()
  // Converts to float32 and uploads (re-allocating storage). Missing normals are computed (area-weighted vertex
  // normals). Triangles are ordered by material (see above). Throws std::invalid_argument if an index is out of
  // range or face_material is neither empty nor #F. Needs a current context.
  void upload(const core::TriMesh& mesh);
  // Overwrites positions (and normals if non-empty) in place; counts must match vertex_count(). For CPU
  // evaluators that keep the topology. Throws std::invalid_argument on a count mismatch.
  void update_vertices(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals);
  // The same from single-precision arrays (uploaded as they are: no conversion pass).
  void update_vertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals);

  void draw_triangles() const;  // binds the VAO and issues one glDrawElements (every triangle, all materials)
  void draw_range(TriangleRange range) const;  // binds the VAO and draws `range` (nothing when count = 0)
  void bind() const { glBindVertexArray(vao_.id()); }

  GLuint vertex_array() const { return vao_.id(); }
  GLuint position_buffer() const { return positions_.id(); }  // #V×3 float, world units
  GLuint normal_buffer() const { return normals_.id(); }      // #V×3 float, unit
  GLuint index_buffer() const { return indices_.id(); }       // #F×3 uint32
  GLuint uv_buffer() const { return uvs_.id(); }              // #V×2 float (empty buffer when !has_uvs())
  bool has_uvs() const { return has_uvs_; }
  // Binds attribute 3 of the bound VAO to uv_buffer(), or to the constant (0,0) without uvs (the GLSL vertex FFD
  // path draws through a VAO of its own).
  void bind_uvs_to_bound_vao() const;
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t triangle_count() const { return triangle_count_; }
  // Surface triangles (kMaterialSurface): [0, S); inside triangles (any other material): [S, #F).
  TriangleRange surface_range() const { return {0, triangle_count_ - inside_count_}; }
  TriangleRange inside_range() const { return {triangle_count_ - inside_count_, inside_count_}; }
  // One range per slot present, in slot order (kMaterialInside last); one range {0, all} for a mesh without
  // face_material.
  const std::vector<MaterialRange>& material_ranges() const { return material_ranges_; }

 private:
  VertexArray vao_;
  Buffer positions_, normals_, uvs_, indices_;
  std::size_t vertex_count_ = 0, triangle_count_ = 0, inside_count_ = 0;
  bool has_uvs_ = false;
  std::vector<MaterialRange> material_ranges_;
};

// Area-weighted vertex normals of `mesh` (#V×3 unit; zero-area neighbourhoods get (0,1,0)).
std::vector<glm::vec3> vertex_normals(const core::TriMesh& mesh);

}  // namespace trispline::gpu
