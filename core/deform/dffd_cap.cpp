// DFFD caps: the cross-section loops of a mesh split at a parameter plane, triangulated with holes by CGAL's
// constrained Delaunay triangulation. See dffd_cap.h. Source: seed §6.3.2, Fig. 6.2b (caps); the nesting-depth
// marking is the CGAL 2D Triangulations manual's "polygon with holes" example (mark_domains).
#include "core/deform/dffd_cap.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace trispline::core {
namespace {

constexpr double kCutTol = 1e-9;  // |params[axis] − (u0 ∓ eps)| of a cut vertex (see dffd_cap.h)

struct VertexInfo {
  std::int64_t index = -1;  // mesh vertex; -1 for a vertex CGAL made at a constraint crossing
};
struct FaceInfo {
  int nesting = -1;  // number of constrained edges crossed from the infinite face; -1 = not yet reached
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Tri = std::array<std::uint32_t, 3>;

// Flood fill from `start` without crossing constrained edges; constrained edges met go to `border`.
void mark_region(Cdt& cdt, Cdt::Face_handle start, int level, std::deque<Cdt::Edge>& border) {
  if (start->info().nesting != -1) return;
  std::deque<Cdt::Face_handle> queue{start};
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    if (f->info().nesting != -1) continue;
    f->info().nesting = level;
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle n = f->neighbor(i);
      if (n->info().nesting != -1) continue;
      if (cdt.is_constrained(Cdt::Edge(f, i)))
        border.emplace_back(f, i);
      else
        queue.push_back(n);
    }
  }
}

// Nesting depth of every face: 0 outside all loops, 1 inside one, 2 in a hole, … (inside = odd).
void mark_nesting(Cdt& cdt) {
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
  std::deque<Cdt::Edge> border;
  mark_region(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    const Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) mark_region(cdt, n, e.first->info().nesting + 1, border);
  }
}

// Boundary half-edges a→b of one side, chained into closed loops (vertex sequences in the half-edges' direction).
// Walks are deterministic: chain heads (more out- than in-edges) first, in increasing vertex order, then loops
// from the smallest vertex with an unused edge; at a branching vertex the smallest unused successor is taken.
// Walks that cannot close are counted in `open_chains` and dropped.
std::vector<std::vector<std::uint32_t>> chain_loops(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges,
                                                    std::size_t& open_chains) {
  std::map<std::uint32_t, std::vector<std::uint32_t>> out;  // sorted successors, consumed from the front
  std::map<std::uint32_t, int> in;
  for (const auto& [a, b] : edges) out[a].push_back(b), ++in[b], out.try_emplace(b);
  std::map<std::uint32_t, std::size_t> next_unused;
  for (auto& [v, succ] : out) std::sort(succ.begin(), succ.end()), next_unused[v] = 0;
  auto take = [&](std::uint32_t v, std::uint32_t& w) {
    std::size_t& k = next_unused[v];
    if (k >= out[v].size()) return false;
    w = out[v][k++];
    return true;
  };
  auto remaining = [&](std::uint32_t v) { return out[v].size() - next_unused[v]; };

  for (const auto& [v, succ] : out) {  // open chains start where out-degree exceeds in-degree
    const int excess = static_cast<int>(succ.size()) - in[v];
    for (int k = 0; k < excess && remaining(v) > 0; ++k) {
      std::uint32_t cur = v, w = 0;
      while (take(cur, w)) cur = w;
      ++open_chains;
    }
  }
  std::vector<std::vector<std::uint32_t>> loops;
  for (const auto& [v, succ] : out) {
    while (remaining(v) > 0) {
      std::vector<std::uint32_t> loop{v};
      std::uint32_t cur = v, w = 0;
      bool closed = false;
      while (take(cur, w)) {
        if (w == v) {
          closed = true;
          break;
        }
        loop.push_back(w);
        cur = w;
      }
      if (closed && loop.size() >= 3)
        loops.push_back(std::move(loop));
      else
        ++open_chains;
    }
  }
  return loops;
}

// Triangulates one side's loops in the (axis+1, axis+2) parameter plane; inside faces (odd nesting) in CCW order
// there, i.e. facing +axis (the cyclic order (axis, axis+1, axis+2) is right-handed).
std::vector<Tri> triangulate_loops(const std::vector<std::vector<std::uint32_t>>& loops,
                                   const std::vector<glm::dvec3>& params, int axis) {
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  std::vector<std::uint32_t> verts;
  for (const auto& loop : loops) verts.insert(verts.end(), loop.begin(), loop.end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());

  Cdt cdt;
  std::unordered_map<std::uint32_t, Cdt::Vertex_handle> handle;
  handle.reserve(verts.size());
  for (std::uint32_t v : verts) {  // increasing index: a 2D duplicate maps to the smallest index at that point
    const Cdt::Vertex_handle h = cdt.insert(K::Point_2(params[v][a1], params[v][a2]));
    if (h->info().index < 0) h->info().index = v;
    handle.emplace(v, h);
  }
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Cdt::Vertex_handle ha = handle.at(loop[i]), hb = handle.at(loop[(i + 1) % loop.size()]);
      if (ha != hb) cdt.insert_constraint(ha, hb);
    }
  std::vector<Tri> tris;
  if (cdt.dimension() < 2) return tris;
  mark_nesting(cdt);
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (f->info().nesting % 2 != 1) continue;
    const std::int64_t i0 = f->vertex(0)->info().index, i1 = f->vertex(1)->info().index,
                       i2 = f->vertex(2)->info().index;
    if (i0 < 0 || i1 < 0 || i2 < 0) continue;  // touches a constraint crossing (self-intersecting section)
    tris.push_back({static_cast<std::uint32_t>(i0), static_cast<std::uint32_t>(i1), static_cast<std::uint32_t>(i2)});
  }
  // Canonical order, independent of CGAL's face storage: smallest index first (winding kept), then sorted.
  for (Tri& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(tris.begin(), tris.end());
  return tris;
}

// Loops (boundary half-edges a→b of the mesh) that `tris` do not close exactly: a closing cap has the reversed
// half-edge b→a once and pairs every other half-edge of its own with its reverse. One flag per loop.
std::vector<bool> unclosed_loops(const std::vector<std::vector<std::uint32_t>>& loops, const std::vector<Tri>& tris) {
  auto key = [](std::uint32_t a, std::uint32_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; };
  std::unordered_map<std::uint64_t, int> half;  // cap half-edges a→b
  for (const Tri& t : tris)
    for (int e = 0; e < 3; ++e) ++half[key(t[e], t[(e + 1) % 3])];
  std::unordered_map<std::uint32_t, std::size_t> loop_of;
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (std::uint32_t v : loops[i]) loop_of.emplace(v, i);
  std::vector<bool> bad(loops.size(), false);
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (std::size_t j = 0; j < loops[i].size(); ++j) {
      const std::uint32_t a = loops[i][j], b = loops[i][(j + 1) % loops[i].size()];
      auto it = half.find(key(b, a));
      if (it == half.end() || it->second != 1 || half.count(key(a, b))) {
        bad[i] = true;
        continue;
      }
      it->second = 0;  // consumed by the loop
    }
  for (const auto& [k, n] : half) {
    if (n == 0) continue;
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k & 0xffffffffu);
    auto rev = half.find(key(b, a));
    if (n == 1 && rev != half.end() && rev->second == 1) continue;
    for (std::uint32_t v : {a, b}) {
      auto l = loop_of.find(v);
      if (l != loop_of.end()) bad[l->second] = true;
    }
  }
  return bad;
}

}  // namespace

CapStats cap_split_openings(MeshSplit& split, int axis, double u0, double eps, std::uint8_t material) {
  TriMesh& mesh = split.mesh;
  const std::size_t nv = mesh.vertex_count();
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("cap_split_openings: axis must be 0, 1 or 2, got " + std::to_string(axis));
  if (split.params.size() != nv)
    throw std::invalid_argument("cap_split_openings: params has " + std::to_string(split.params.size()) +
                                " entries, mesh has " + std::to_string(nv) + " vertices");
  if (split.side.size() != nv)
    throw std::invalid_argument("cap_split_openings: side has " + std::to_string(split.side.size()) +
                                " entries, mesh has " + std::to_string(nv) + " vertices");
  for (const glm::uvec3& f : mesh.triangles)
    if (f[0] >= nv || f[1] >= nv || f[2] >= nv)
      throw std::invalid_argument("cap_split_openings: a triangle index is ≥ #V = " + std::to_string(nv));
  if (!mesh.face_material.empty() && mesh.face_material.size() != mesh.triangle_count())
    throw std::invalid_argument("cap_split_openings: face_material has " + std::to_string(mesh.face_material.size()) +
                                " entries, mesh has " + std::to_string(mesh.triangle_count()) + " triangles");

  // Cut vertices: side s ∈ {−1, +1} and params[axis] = u0 + s·eps.
  std::vector<std::int8_t> cut(nv, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    const int s = split.side[v];
    if ((s == -1 || s == 1) && std::abs(split.params[v][axis] - (u0 + s * eps)) <= kCutTol)
      cut[v] = static_cast<std::int8_t>(s);
  }
  // Undirected edge use counts among edges with both ends cut on the same side.
  auto key = [](std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  };
  std::unordered_map<std::uint64_t, int> uses;
  for (const glm::uvec3& f : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = f[e], b = f[(e + 1) % 3];
      if (cut[a] != 0 && cut[a] == cut[b]) ++uses[key(a, b)];
    }
  // Boundary half-edges (used once), per side, in triangle order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary[2];
  for (const glm::uvec3& f : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = f[e], b = f[(e + 1) % 3];
      if (cut[a] != 0 && cut[a] == cut[b] && uses[key(a, b)] == 1) boundary[cut[a] < 0 ? 0 : 1].emplace_back(a, b);
    }

  CapStats stats;
  std::vector<Tri> caps;
  for (int k = 0; k < 2; ++k) {  // k = 0: minus side (faces +axis), k = 1: plus side (faces −axis)
    const auto loops = chain_loops(boundary[k], stats.open_chains);
    stats.loops += loops.size();
    auto oriented = [&](std::vector<Tri> tris) {
      if (k == 1)
        for (Tri& t : tris) std::swap(t[1], t[2]);
      return tris;
    };
    std::vector<Tri> tris = oriented(triangulate_loops(loops, split.params, axis));
    std::vector<bool> bad = unclosed_loops(loops, tris);
    if (std::find(bad.begin(), bad.end(), true) != bad.end()) {
      // Degenerate sections (loops touching or crossing in the plane, 2-D duplicates of distinct vertices): the
      // well-formed loops are triangulated again without the others, which get a fan so the side stays closed.
      std::vector<std::vector<std::uint32_t>> good;
      for (std::size_t i = 0; i < loops.size(); ++i)
        if (!bad[i]) good.push_back(loops[i]);
      tris = oriented(triangulate_loops(good, split.params, axis));
      if (std::find(unclosed_loops(good, tris).begin(), unclosed_loops(good, tris).end(), true) !=
          unclosed_loops(good, tris).end()) {
        tris.clear();
        std::fill(bad.begin(), bad.end(), true);
      }
      for (std::size_t i = 0; i < loops.size(); ++i)
        if (bad[i]) {
          const auto& L = loops[i];
          for (std::size_t j = 1; j + 1 < L.size(); ++j) tris.push_back({L[0], L[j + 1], L[j]});
          ++stats.fan_loops;
        }
    }
    caps.insert(caps.end(), tris.begin(), tris.end());
  }
  if (caps.empty()) return stats;
  if (mesh.face_material.empty()) mesh.face_material.assign(mesh.triangles.size(), kMaterialSurface);
  for (const Tri& t : caps) {
    mesh.triangles.emplace_back(t[0], t[1], t[2]);
    mesh.face_material.push_back(material);
  }
  stats.triangles = caps.size();
  return stats;
}

}  // namespace trispline::core
