// DFFD caps: the cross-section loops of a mesh split at a parameter plane, triangulated with holes
// (core/mesh/planar_triangulation.h). See dffd_cap.h. Source: seed §6.3.2, Fig. 6.2b (caps).
#include "core/dffd/dffd_cap.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/mesh/planar_triangulation.h"

namespace trispline::core {
namespace {

constexpr double kCutTol = 1e-9;  // |params[axis] − (u0 ∓ eps)| of a cut vertex (see dffd_cap.h)

using Tri = std::array<std::uint32_t, 3>;

// Boundary half-edges a→b of one side, chained into closed loops (vertex sequences in the half-edges' direction).
// Walks are deterministic: chain heads (more out- than in-edges) first, in increasing vertex order, then loops
// from the smallest vertex with an unused edge; at a branching vertex the smallest unused successor is taken.
// Walks that cannot close are counted in `open_chains` and dropped.
std::vector<std::vector<std::uint32_t>> chain_loops(std::vector<std::pair<std::uint32_t, std::uint32_t>> edges,
                                                    std::size_t& open_chains) {
  // Compact adjacency: vertices sorted (dense ids), edges sorted by (from, to) so each vertex's successors are a
  // sorted run consumed from the front.
  std::vector<std::uint32_t> verts;
  verts.reserve(2 * edges.size());
  for (const auto& [a, b] : edges) verts.push_back(a), verts.push_back(b);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  auto id = [&](std::uint32_t v) {
    return static_cast<std::size_t>(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin());
  };
  std::sort(edges.begin(), edges.end());
  std::vector<std::size_t> begin(verts.size() + 1, 0), next(verts.size());
  std::vector<int> in(verts.size(), 0);
  for (const auto& [a, b] : edges) ++begin[id(a) + 1], ++in[id(b)];
  for (std::size_t i = 0; i < verts.size(); ++i) begin[i + 1] += begin[i];
  for (std::size_t i = 0; i < verts.size(); ++i) next[i] = begin[i];
  auto remaining = [&](std::size_t i) { return begin[i + 1] - next[i]; };
  auto take = [&](std::size_t i, std::size_t& j) {  // next unused successor of vertex id i, as an id
    if (next[i] >= begin[i + 1]) return false;
    j = id(edges[next[i]++].second);
    return true;
  };

  for (std::size_t v = 0; v < verts.size(); ++v) {  // open chains start where out-degree exceeds in-degree
    const int excess = static_cast<int>(begin[v + 1] - begin[v]) - in[v];
    for (int k = 0; k < excess && remaining(v) > 0; ++k) {
      std::size_t cur = v, w = 0;
      while (take(cur, w)) cur = w;
      ++open_chains;
    }
  }
  std::vector<std::vector<std::uint32_t>> loops;
  for (std::size_t v = 0; v < verts.size(); ++v) {
    while (remaining(v) > 0) {
      std::vector<std::uint32_t> loop{verts[v]};
      std::size_t cur = v, w = 0;
      bool closed = false;
      while (take(cur, w)) {
        if (w == v) {
          closed = true;
          break;
        }
        loop.push_back(verts[w]);
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
  return triangulate_nested_loops(loops, [&](std::uint32_t v) { return glm::dvec2(params[v][a1], params[v][a2]); });
}

// Loops (boundary half-edges a→b of the mesh) that `tris` do not close exactly: a closing cap has the reversed
// half-edge b→a once and pairs every other half-edge of its own with its reverse. One flag per loop.
std::vector<bool> unclosed_loops(const std::vector<std::vector<std::uint32_t>>& loops, const std::vector<Tri>& tris) {
  auto key = [](std::uint32_t a, std::uint32_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; };
  // Cap half-edges a→b with their use counts: sorted unique keys (binary search instead of a hash map).
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * tris.size());
  for (const Tri& t : tris)
    for (int e = 0; e < 3; ++e) keys.push_back(key(t[e], t[(e + 1) % 3]));
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<std::uint64_t, int>> half;  // (key, count)
  for (std::uint64_t k : keys) {
    if (!half.empty() && half.back().first == k)
      ++half.back().second;
    else
      half.emplace_back(k, 1);
  }
  auto find = [&](std::uint64_t k) -> std::pair<std::uint64_t, int>* {
    auto it = std::lower_bound(half.begin(), half.end(), std::make_pair(k, 0),
                               [](const auto& x, const auto& y) { return x.first < y.first; });
    return it != half.end() && it->first == k ? &*it : nullptr;
  };
  std::vector<std::pair<std::uint32_t, std::size_t>> loop_of;  // (vertex, first loop holding it)
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (std::uint32_t v : loops[i]) loop_of.emplace_back(v, i);
  std::stable_sort(loop_of.begin(), loop_of.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<bool> bad(loops.size(), false);
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (std::size_t j = 0; j < loops[i].size(); ++j) {
      const std::uint32_t a = loops[i][j], b = loops[i][(j + 1) % loops[i].size()];
      auto* rev = find(key(b, a));
      if (rev == nullptr || rev->second != 1 || find(key(a, b)) != nullptr) {
        bad[i] = true;
        continue;
      }
      rev->second = 0;  // consumed by the loop
    }
  for (const auto& [k, n] : half) {
    if (n == 0) continue;
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k & 0xffffffffu);
    const auto* rev = find(key(b, a));
    if (n == 1 && rev != nullptr && rev->second == 1) continue;
    for (std::uint32_t v : {a, b}) {
      auto l = std::lower_bound(loop_of.begin(), loop_of.end(), std::make_pair(v, std::size_t{0}),
                                [](const auto& x, const auto& y) { return x.first < y.first; });
      if (l != loop_of.end() && l->first == v) bad[l->second] = true;
    }
  }
  return bad;
}

// Cut vertices of one side that stand at the same point of the section (2-D distance in the two other parameter
// coordinates ≤ kWeldTol): the copies a mesh carries along its seams (a box's hard edges, UV seams) are cut into
// separate vertices at one place. Returns (vertex, representative) sorted by vertex, the representative the
// smallest vertex index of its group, so loops are chained on the welded surface. Deterministic.
constexpr double kWeldTol = 1e-9;

std::vector<std::pair<std::uint32_t, std::uint32_t>> weld_cut_vertices(const std::vector<std::uint32_t>& verts,
                                                                       const std::vector<std::int8_t>& cut,
                                                                       const std::vector<glm::dvec3>& params,
                                                                       int axis) {
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> rep;  // (vertex, representative), sorted by vertex
  rep.reserve(verts.size());
  for (std::uint32_t v : verts) rep.emplace_back(v, v);
  std::sort(rep.begin(), rep.end());
  rep.erase(std::unique(rep.begin(), rep.end()), rep.end());
  auto parent = [&](std::uint32_t v) -> std::uint32_t& {
    return std::lower_bound(rep.begin(), rep.end(), std::make_pair(v, std::uint32_t{0}))->second;
  };
  auto root = [&](std::uint32_t v) {
    while (parent(v) != v) v = parent(v);
    return v;
  };
  // Grid cells of side kWeldTol: a vertex is compared with those in its own and the 8 neighbouring cells.
  using Cell = std::array<std::int64_t, 3>;  // (side, cell along a1, cell along a2)
  auto cell_of = [&](std::uint32_t v) {
    auto index = [](double x) {  // params are finite; clamped so the conversion is defined
      return static_cast<std::int64_t>(std::clamp(std::floor(x / kWeldTol), -1e15, 1e15));
    };
    return Cell{cut[v], index(params[v][a1]), index(params[v][a2])};
  };
  std::vector<std::pair<Cell, std::uint32_t>> cells;
  cells.reserve(rep.size());
  for (const auto& [v, r] : rep) cells.emplace_back(cell_of(v), v);
  std::sort(cells.begin(), cells.end());
  for (const auto& [c, x] : cells)
    for (std::int64_t d1 = -1; d1 <= 1; ++d1)
      for (std::int64_t d2 = -1; d2 <= 1; ++d2) {
        const Cell n{c[0], c[1] + d1, c[2] + d2};
        for (auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(n, std::uint32_t{0}));
             it != cells.end() && it->first == n; ++it) {
          const std::uint32_t y = it->second;
          if (y <= x || std::abs(params[y][a1] - params[x][a1]) > kWeldTol ||
              std::abs(params[y][a2] - params[x][a2]) > kWeldTol)
            continue;
          const std::uint32_t rx = root(x), ry = root(y);
          if (rx != ry) parent(std::max(rx, ry)) = std::min(rx, ry);
        }
      }
  for (auto& [v, r] : rep) r = root(v);
  return rep;
}

// Textured caps: every vertex `caps` use is copied (ascending by the vertex copied), the copy carrying the cap's
// planar uv (CapTexturing), and `caps` re-indexed to the copies.
void give_caps_own_vertices(MeshSplit& split, std::vector<Tri>& caps, int axis, const CapTexturing& texturing) {
  const glm::dvec3& uv_per_param = texturing.uv_per_param;
  const glm::dvec3& plane_normal = texturing.plane_normals[axis];
  TriMesh& mesh = split.mesh;
  const std::size_t nv = mesh.vertex_count();
  std::vector<std::uint32_t> used;
  used.reserve(caps.size() * 3);
  for (const Tri& t : caps) used.insert(used.end(), t.begin(), t.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  if (mesh.uvs.empty()) mesh.uvs.assign(nv, glm::dvec2(0.0));
  const bool normals = !mesh.normals.empty();
  const std::size_t total = nv + used.size();
  mesh.positions.reserve(total);
  mesh.uvs.reserve(total);
  if (normals) mesh.normals.reserve(total);
  split.params.reserve(total);
  split.side.reserve(total);
  for (std::uint32_t v : used) {
    mesh.positions.push_back(mesh.positions[v]);
    if (normals)
      mesh.normals.push_back(plane_normal == glm::dvec3(0.0) ? mesh.normals[v]
                                                             : (split.side[v] < 0 ? plane_normal : -plane_normal));
    const glm::dvec3 p = split.params[v], q = p - texturing.param_offset;
    mesh.uvs.emplace_back(q[a] * uv_per_param[a], q[b] * uv_per_param[b]);
    split.params.push_back(p);
    split.side.push_back(split.side[v]);
  }
  for (Tri& t : caps)
    for (std::uint32_t& v : t)
      v = static_cast<std::uint32_t>(nv + (std::lower_bound(used.begin(), used.end(), v) - used.begin()));
}

// Red-green refinement of the textured caps' inner edges longer than max_edge (in-plane parameter units, the larger of
// the two differences); the loop's edges (used by one cap triangle) are kept. New vertices are appended in the order
// their edges are first met (triangle order, edge order): deterministic.
void refine_caps(MeshSplit& split, std::vector<Tri>& caps, int axis, double max_edge) {
  constexpr int kMaxLevels = 16;
  constexpr std::size_t kMaxCapTriangles = std::size_t(4) << 20;
  TriMesh& mesh = split.mesh;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  const bool normals = !mesh.normals.empty();
  auto key = [](std::uint32_t x, std::uint32_t y) {
    return (static_cast<std::uint64_t>(std::min(x, y)) << 32) | std::max(x, y);
  };
  for (int level = 0; level < kMaxLevels && caps.size() < kMaxCapTriangles / 4; ++level) {
    std::vector<std::uint64_t> uses;
    uses.reserve(caps.size() * 3);
    for (const Tri& t : caps)
      for (int e = 0; e < 3; ++e) uses.push_back(key(t[e], t[(e + 1) % 3]));
    std::sort(uses.begin(), uses.end());
    auto inner = [&](std::uint64_t k) {
      const auto r = std::equal_range(uses.begin(), uses.end(), k);
      return r.second - r.first >= 2;
    };
    auto too_long = [&](std::uint32_t x, std::uint32_t y) {
      const glm::dvec3 d = split.params[x] - split.params[y];
      return std::max(std::abs(d[a]), std::abs(d[b])) > max_edge;
    };
    std::unordered_map<std::uint64_t, std::uint32_t>
        mids;  // edge key → its midpoint vertex (looked up, never iterated)
    auto midpoint = [&](std::uint32_t x, std::uint32_t y) -> std::uint32_t {
      const auto [it, fresh] = mids.try_emplace(key(x, y), static_cast<std::uint32_t>(mesh.positions.size()));
      if (!fresh) return it->second;
      const std::uint32_t v = it->second;
      mesh.positions.push_back(0.5 * (mesh.positions[x] + mesh.positions[y]));
      if (normals) mesh.normals.push_back(mesh.normals[x]);
      mesh.uvs.push_back(0.5 * (mesh.uvs[x] + mesh.uvs[y]));
      split.params.push_back(0.5 * (split.params[x] + split.params[y]));
      split.side.push_back(split.side[x]);
      return v;
    };
    std::vector<Tri> out;
    out.reserve(caps.size() * 2);
    bool any = false;
    for (const Tri& t : caps) {
      std::array<std::int64_t, 3> m{-1, -1, -1};  // midpoint of edge e = (t[e], t[e+1])
      int split_edges = 0;
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t x = t[e], y = t[(e + 1) % 3];
        if (too_long(x, y) && inner(key(x, y))) m[e] = midpoint(x, y), ++split_edges;
      }
      if (split_edges == 0) {
        out.push_back(t);
        continue;
      }
      any = true;
      if (split_edges == 3) {
        const auto m0 = std::uint32_t(m[0]), m1 = std::uint32_t(m[1]), m2 = std::uint32_t(m[2]);
        out.push_back({t[0], m0, m2});
        out.push_back({m0, t[1], m1});
        out.push_back({m2, m1, t[2]});
        out.push_back({m0, m1, m2});
        continue;
      }
      // Rotate so that edge 0 is split (and, with two, edge 1 too or edge 2 too).
      int r = 0;
      while (m[r] < 0) ++r;
      if (split_edges == 2 && m[(r + 2) % 3] >= 0) r = (r + 2) % 3;  // the run of split edges starts at r
      const std::uint32_t v0 = t[r], v1 = t[(r + 1) % 3], v2 = t[(r + 2) % 3];
      const auto m0 = std::uint32_t(m[r]);
      if (split_edges == 1) {
        out.push_back({v0, m0, v2});
        out.push_back({m0, v1, v2});
      } else {
        const auto m1 = std::uint32_t(m[(r + 1) % 3]);
        out.push_back({v0, m0, v2});
        out.push_back({m0, v1, m1});
        out.push_back({m0, m1, v2});
      }
    }
    caps = std::move(out);
    if (!any) break;
  }
}

}  // namespace

CapStats cap_split_openings(MeshSplit& split, int axis, double u0, double eps, MaterialSlot material,
                            const CapTexturing& texturing) {
  TriMesh& mesh = split.mesh;
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("cap_split_openings: axis must be 0, 1 or 2, got " + std::to_string(axis));
  if (split.params.size() != nv)
    throw std::invalid_argument("cap_split_openings: params has " + std::to_string(split.params.size()) +
                                " entries, mesh has " + std::to_string(nv) + " vertices");
  if (split.side.size() != nv)
    throw std::invalid_argument("cap_split_openings: side has " + std::to_string(split.side.size()) +
                                " entries, mesh has " + std::to_string(nv) + " vertices");
  if (!mesh.face_material.empty() && mesh.face_material.size() != nf)
    throw std::invalid_argument("cap_split_openings: face_material has " + std::to_string(mesh.face_material.size()) +
                                " entries, mesh has " + std::to_string(nf) + " triangles");
  for (std::uint32_t f : split.touched) {
    if (f >= nf) throw std::invalid_argument("cap_split_openings: touched triangle " + std::to_string(f) + " ≥ #F");
    const glm::uvec3& t = mesh.triangles[f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw std::invalid_argument("cap_split_openings: a triangle index is ≥ #V = " + std::to_string(nv));
  }
  for (std::uint32_t v : split.cut_vertices)
    if (v >= nv) throw std::invalid_argument("cap_split_openings: cut vertex " + std::to_string(v) + " ≥ #V");
  if (texturing.enabled()) {
    const glm::dvec3& s = texturing.uv_per_param;
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.z))
      throw std::invalid_argument("cap_split_openings: texture repeats per parameter unit are not finite");
    if (!std::isfinite(texturing.max_edge) || texturing.max_edge < 0.0)
      throw std::invalid_argument("cap_split_openings: max_edge must be finite and ≥ 0");
    if (!mesh.uvs.empty() && mesh.uvs.size() != nv)
      throw std::invalid_argument("cap_split_openings: uvs must be empty or #V");
    if (!mesh.normals.empty() && mesh.normals.size() != nv)
      throw std::invalid_argument("cap_split_openings: normals must be empty or #V");
  }

  // Cut vertices of this split: side s ∈ {−1, +1} and params[axis] = u0 + s·eps. Only the triangles the split
  // touched can hold two of them (every other triangle lies strictly on one side), so only those are scanned.
  std::vector<std::int8_t> cut(nv, 0);
  for (std::uint32_t v : split.cut_vertices) {
    const int s = split.side[v];
    if ((s == -1 || s == 1) && std::abs(split.params[v][axis] - (u0 + s * eps)) <= kCutTol)
      cut[v] = static_cast<std::int8_t>(s);
  }
  std::vector<std::uint32_t> cut_list;
  for (std::uint32_t v : split.cut_vertices)
    if (cut[v] != 0) cut_list.push_back(v);
  const auto welded = weld_cut_vertices(cut_list, cut, split.params, axis);
  auto rep = [&](std::uint32_t v) {
    return std::lower_bound(welded.begin(), welded.end(), std::make_pair(v, std::uint32_t{0}))->second;
  };
  // Undirected edge use counts among edges with both ends cut on the same side, on the welded vertices.
  auto key = [](std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  };
  std::vector<std::uint64_t> uses;  // one key per use, sorted: an edge used once appears once
  uses.reserve(4 * split.cut_vertices.size());
  for (std::uint32_t fi : split.touched) {
    const glm::uvec3& f = mesh.triangles[fi];
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = f[e], b = f[(e + 1) % 3];
      if (cut[a] != 0 && cut[a] == cut[b]) uses.push_back(key(rep(a), rep(b)));
    }
  }
  std::sort(uses.begin(), uses.end());
  auto used_once = [&](std::uint64_t k) {
    const auto r = std::equal_range(uses.begin(), uses.end(), k);
    return r.second - r.first == 1;
  };
  // Boundary half-edges (used once), per side, in triangle order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary[2];
  for (std::uint32_t fi : split.touched) {
    const glm::uvec3& f = mesh.triangles[fi];
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = f[e], b = f[(e + 1) % 3];
      if (cut[a] == 0 || cut[a] != cut[b]) continue;
      const std::uint32_t ra = rep(a), rb = rep(b);
      if (ra != rb && used_once(key(ra, rb))) boundary[cut[a] < 0 ? 0 : 1].emplace_back(ra, rb);
    }
  }

  // The two sides are independent (their own loops, read-only params): triangulated concurrently, merged in order.
  struct Side {
    std::vector<Tri> tris;
    std::size_t loops = 0, open_chains = 0, fan_loops = 0;
  };
  Side sides[2];
  auto cap_side = [&](int k) {  // k = 0: minus side (faces +axis), k = 1: plus side (faces −axis)
    Side& out = sides[k];
    const auto loops = chain_loops(std::move(boundary[k]), out.open_chains);
    out.loops = loops.size();
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
      const std::vector<bool> still_bad = unclosed_loops(good, tris);
      if (std::find(still_bad.begin(), still_bad.end(), true) != still_bad.end()) {
        tris.clear();
        std::fill(bad.begin(), bad.end(), true);
      }
      for (std::size_t i = 0; i < loops.size(); ++i)
        if (bad[i]) {
          const auto& L = loops[i];
          for (std::size_t j = 1; j + 1 < L.size(); ++j) tris.push_back({L[0], L[j + 1], L[j]});
          ++out.fan_loops;
        }
    }
    out.tris = std::move(tris);
  };
  tbb::parallel_invoke([&] { cap_side(0); }, [&] { cap_side(1); });
  CapStats stats;
  std::vector<Tri> caps;
  for (const Side& side : sides) {
    stats.loops += side.loops;
    stats.open_chains += side.open_chains;
    stats.fan_loops += side.fan_loops;
    caps.insert(caps.end(), side.tris.begin(), side.tris.end());
  }
  if (caps.empty()) return stats;
  if (texturing.enabled()) {
    give_caps_own_vertices(split, caps, axis, texturing);
    if (texturing.max_edge > 0.0) refine_caps(split, caps, axis, texturing.max_edge);
  }
  if (mesh.face_material.empty()) mesh.face_material.assign(mesh.triangles.size(), kMaterialSurface);
  for (const Tri& t : caps) {
    mesh.triangles.emplace_back(t[0], t[1], t[2]);
    mesh.face_material.push_back(material);
  }
  stats.triangles = caps.size();
  return stats;
}

}  // namespace trispline::core
