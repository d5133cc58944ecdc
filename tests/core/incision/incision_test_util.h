// Shared helpers of the incision tests: topology checks through OpenMesh and a plain edge count, and frames cut
// from a camera looking at a mesh.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "core/incision/incision.h"
#include "core/mesh/tri_mesh.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/camera.h"

namespace trispline::core::test {

struct Topology {
  std::size_t nonmanifold_edges = 0;              // undirected edges with > 2 faces
  std::size_t boundary_edges = 0;                 // undirected edges with exactly one face
  std::size_t repeated_halfedges = 0;             // directed edges used twice (orientation broken)
  std::size_t duplicate_faces = 0;                // same vertex set twice
  std::size_t degenerate_faces = 0;               // a repeated vertex index
  std::size_t openmesh_rejected = 0;              // faces OpenMesh's add_face refuses (complex edge / vertex)
  std::size_t openmesh_nonmanifold_vertices = 0;  // vertices OpenMesh sees as not manifold
  std::size_t boundary_loops = 0;                 // boundary loops of the OpenMesh halfedge structure
};

inline Topology topology(const TriMesh& m) {
  Topology t;
  std::map<std::pair<unsigned, unsigned>, int> undirected, directed;
  std::set<std::array<unsigned, 3>> faces;
  for (const glm::uvec3& f : m.triangles) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) ++t.degenerate_faces;
    std::array<unsigned, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    if (!faces.insert(key).second) ++t.duplicate_faces;
    for (int e = 0; e < 3; ++e) {
      const unsigned a = f[e], b = f[(e + 1) % 3];
      ++undirected[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
    }
  }
  for (const auto& [e, n] : undirected) {
    if (n > 2) ++t.nonmanifold_edges;
    if (n == 1) ++t.boundary_edges;
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

// The frame of a stroke through world points `pts` (projected to pixels of `cam`) on `mesh`.
inline std::optional<IncisionFrame> frame_through(const TriMesh& mesh, const Camera& cam,
                                                  const std::vector<glm::dvec3>& pts,
                                                  std::vector<glm::dvec2>* px_out = nullptr) {
  RayCaster rc;
  rc.add_mesh(mesh);
  rc.commit();
  std::vector<glm::dvec2> px;
  for (const glm::dvec3& p : pts) {
    const glm::dvec3 q = cam.project(p);
    px.emplace_back(q.x, q.y);
  }
  if (px_out) *px_out = px;
  return fit_incision_frame(px, cam, rc);
}

// Points along the straight segment a → b (count ≥ 2).
inline std::vector<glm::dvec3> segment(const glm::dvec3& a, const glm::dvec3& b, int count) {
  std::vector<glm::dvec3> out;
  for (int i = 0; i < count; ++i) out.push_back(a + (b - a) * (double(i) / (count - 1)));
  return out;
}

}  // namespace trispline::core::test
