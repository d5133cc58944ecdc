#include "core/mesh/mesh_decimate.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace trispline::core {
namespace {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

}  // namespace

std::vector<glm::uvec3> decimated_triangles(const TriMesh& mesh, std::size_t target_vertices) {
  if (target_vertices >= mesh.vertex_count() || mesh.triangles.empty()) return mesh.triangles;
  OmMesh m;
  m.reserve(mesh.vertex_count(), 3 * mesh.triangle_count(), mesh.triangle_count());
  std::vector<OmMesh::VertexHandle> vh;
  vh.reserve(mesh.vertex_count());
  for (const glm::dvec3& p : mesh.positions) vh.push_back(m.add_vertex(OmMesh::Point(p.x, p.y, p.z)));
  for (const glm::uvec3& t : mesh.triangles) {
    if (t.x >= vh.size() || t.y >= vh.size() || t.z >= vh.size()) return mesh.triangles;
    if (!m.add_face(vh[t.x], vh[t.y], vh[t.z]).is_valid()) return mesh.triangles;  // not a manifold: keep it whole
  }
  m.request_vertex_status();
  m.request_edge_status();
  m.request_face_status();
  m.request_face_normals();
  m.update_face_normals();
  for (const OmMesh::VertexHandle v : m.vertices())
    if (m.is_boundary(v)) m.status(v).set_locked(true);
  OpenMesh::Decimater::DecimaterT<OmMesh> decimater(m);
  OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<OmMesh>::Handle flipping;
  decimater.add(quadric);
  decimater.add(flipping);
  decimater.module(quadric).unset_max_err();
  if (!decimater.initialize()) return mesh.triangles;
  if (decimater.decimate_to(target_vertices) == 0) return mesh.triangles;  // nothing could be collapsed
  // No garbage collection: the handles' indices are still the input's.
  std::vector<glm::uvec3> out;
  for (const OmMesh::FaceHandle f : m.faces()) {
    if (m.status(f).deleted()) continue;
    glm::uvec3 t;
    int c = 0;
    for (const OmMesh::VertexHandle v : m.fv_range(f)) t[c++] = static_cast<unsigned>(v.idx());
    out.push_back(t);
  }
  return out.empty() ? mesh.triangles : out;
}

std::size_t used_vertex_count(const std::vector<glm::uvec3>& triangles, std::size_t vertex_count) {
  std::vector<unsigned char> used(vertex_count, 0);
  std::size_t n = 0;
  for (const glm::uvec3& t : triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] < vertex_count && !used[t[c]]) used[t[c]] = 1, ++n;
  return n;
}

}  // namespace trispline::core
