// Mesh topology checks shared by the DFFD and incision tests: edge and face counts on our arrays (boundary,
// non-manifold and repeated half-edges, duplicate and degenerate faces) and OpenMesh's view of the same triangles
// (faces its add_face refuses at complex edges or vertices, non-manifold vertices, boundary loops).
#pragma once

#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core::test {

struct Topology {
  std::size_t nonmanifold_edges = 0;                    // undirected edges with > 2 faces
  std::size_t boundary_edges = 0;                       // undirected edges with exactly one face
  std::size_t repeated_halfedges = 0;                   // directed edges used twice (orientation broken)
  std::size_t duplicate_faces = 0;                      // same vertex set twice
  std::size_t degenerate_faces = 0;                     // a repeated vertex index
  std::size_t openmesh_rejected = 0;                    // faces OpenMesh's add_face refuses (complex edge / vertex)
  std::size_t openmesh_nonmanifold_vertices = 0;        // vertices OpenMesh sees as not manifold
  std::size_t boundary_loops = 0;                       // boundary loops of the OpenMesh halfedge structure
  std::vector<std::pair<unsigned, unsigned>> boundary;  // the boundary edges (lower index first), sorted
};

// Undirected edge (lower index first) → the number of faces that use it.
inline std::map<std::pair<unsigned, unsigned>, int> edge_faces(const TriMesh& m) {
  std::map<std::pair<unsigned, unsigned>, int> undirected;
  for (const glm::uvec3& f : m.triangles)
    for (int e = 0; e < 3; ++e) ++undirected[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  return undirected;
}

inline Topology topology(const TriMesh& m) {
  Topology t;
  std::map<std::pair<unsigned, unsigned>, int> undirected, directed;
  std::set<std::array<unsigned, 3>> faces;
  for (const glm::uvec3& f : m.triangles) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) ++t.degenerate_faces;
    std::array<unsigned, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    if (!faces.insert(key).second) ++t.duplicate_faces;
    for (int e = 0; e < 3; ++e) ++directed[{f[e], f[(e + 1) % 3]}];
  }
  undirected = edge_faces(m);
  for (const auto& [e, n] : undirected) {
    if (n > 2) ++t.nonmanifold_edges;
    if (n == 1) {
      ++t.boundary_edges;
      t.boundary.push_back(e);
    }
  }
  for (const auto& [e, n] : directed)
    if (n > 1) ++t.repeated_halfedges;

  using OM = OpenMesh::TriMesh_ArrayKernelT<>;
  OM om;
  std::vector<OM::VertexHandle> vh;
  for (const glm::dvec3& p : m.positions) vh.push_back(om.add_vertex(OM::Point(float(p.x), float(p.y), float(p.z))));
  for (const glm::uvec3& f : m.triangles)
    if (!om.add_face(vh[f.x], vh[f.y], vh[f.z]).is_valid()) ++t.openmesh_rejected;
  for (auto v : om.vertices())
    if (!om.is_manifold(v)) ++t.openmesh_nonmanifold_vertices;
  std::set<int> seen;
  for (auto h : om.halfedges()) {
    if (!om.is_boundary(h) || seen.count(h.idx())) continue;
    ++t.boundary_loops;
    OM::HalfedgeHandle c = h;
    do {
      seen.insert(c.idx());
      c = om.next_halfedge_handle(c);
    } while (c != h && c.is_valid() && !seen.count(c.idx()));
  }
  return t;
}

// A closed, consistently oriented 2-manifold: every edge has two faces, no directed edge is used twice.
inline void expect_closed_manifold(const TriMesh& m) {
  const Topology t = topology(m);
  EXPECT_EQ(t.nonmanifold_edges + t.boundary_edges, 0u);
  EXPECT_EQ(t.repeated_halfedges, 0u);
}

// Success when `t` has no non-manifold edge or vertex, repeated half-edge, duplicate or degenerate face, and
// OpenMesh accepts every face; else a failure naming each non-zero count.
inline ::testing::AssertionResult is_manifold(const Topology& t) {
  const std::pair<const char*, std::size_t> counts[] = {
      {"nonmanifold_edges", t.nonmanifold_edges}, {"repeated_halfedges", t.repeated_halfedges},
      {"duplicate_faces", t.duplicate_faces},     {"degenerate_faces", t.degenerate_faces},
      {"openmesh_rejected", t.openmesh_rejected}, {"openmesh_nonmanifold_vertices", t.openmesh_nonmanifold_vertices}};
  ::testing::AssertionResult r = ::testing::AssertionSuccess();
  bool ok = true;
  for (const auto& [name, n] : counts)
    if (n != 0) {
      if (ok) r = ::testing::AssertionFailure();
      ok = false;
      r << name << " = " << n << "; ";
    }
  return r;
}

}  // namespace trispline::core::test
