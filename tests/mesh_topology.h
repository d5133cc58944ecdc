// Topology checks shared by the DFFD tests: OpenMesh builds the mesh (refusing faces at complex edges or vertices),
// and edge/face counts on our arrays find boundary edges, non-manifold edges and duplicate faces.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct Topology {
  std::size_t rejected_faces = 0;  // OpenMesh refused the face: a complex (non-manifold) edge or vertex
  std::size_t boundary_edges = 0;
  std::size_t non_manifold_edges = 0;  // edges with more than two faces (counted on our arrays)
  std::size_t duplicate_faces = 0;
};

inline Topology topology(const TriMesh& m) {
  Topology t;
  OpenMesh::TriMesh_ArrayKernelT<> om;
  std::vector<OpenMesh::VertexHandle> vh;
  for (const glm::dvec3& p : m.positions) vh.push_back(om.add_vertex({float(p.x), float(p.y), float(p.z)}));
  std::map<std::pair<unsigned, unsigned>, int> edges;
  std::map<std::array<unsigned, 3>, int> faces;
  for (const glm::uvec3& f : m.triangles) {
    if (!om.add_face(vh[f[0]], vh[f[1]], vh[f[2]]).is_valid()) ++t.rejected_faces;
    std::array<unsigned, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    if (++faces[key] == 2) ++t.duplicate_faces;
    for (int e = 0; e < 3; ++e) ++edges[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  }
  for (const auto& [e, n] : edges) {
    if (n == 1) ++t.boundary_edges;
    if (n > 2) ++t.non_manifold_edges;
  }
  return t;
}

}  // namespace trispline::core
