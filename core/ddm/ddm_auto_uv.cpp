// Automatic UV charts for DDM bases. See ddm_auto_uv.h. Sources: CGAL 5.5 Surface_mesh_parameterization
// (LSCM_parameterizer_3: Lévy et al. 2002, least-squares conformal maps, free border with two pinned vertices);
// seed §5.3.1 / §5.4.1 for the use (UV-mapped bases, texels outside the charts diffused and pruned).
#include "core/ddm/ddm_auto_uv.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

constexpr double kGapFactor = 0.003;  // gap between packed charts: this × √(Σ chart box areas)

double world_area(const TriMesh& m, std::size_t f) {
  const glm::uvec3 t = m.triangles[f];
  return 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
}

double signed_area(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  const glm::dvec2 e1 = b - a, e2 = c - a;
  return 0.5 * (e1.x * e2.y - e1.y * e2.x);
}

// One chart: its faces (in growth order) and, once flattened, a uv per face corner.
struct Chart {
  std::vector<int> faces;
  std::vector<glm::dvec2> corner_uv;  // 3 per face, in `faces` order
  glm::dvec2 lo{0.0}, hi{0.0};        // uv box after scaling
};

class Unwrapper {
 public:
  Unwrapper(const TriMesh& mesh, double max_normal_deg) : m_(mesh), cos_max_(std::cos(glm::radians(max_normal_deg))) {
    const std::size_t nf = m_.triangle_count();
    normal_.resize(nf);
    area_.resize(nf);
    for (std::size_t f = 0; f < nf; ++f) {
      const glm::uvec3 t = m_.triangles[f];
      const glm::dvec3 n = glm::cross(m_.positions[t[1]] - m_.positions[t[0]], m_.positions[t[2]] - m_.positions[t[0]]);
      const double len = glm::length(n);
      normal_[f] = len > 0.0 ? n / len : glm::dvec3(0.0);
      area_[f] = 0.5 * len;
    }
    // Face adjacency through undirected edges (sorted: deterministic); more than two faces on an edge is refused.
    std::vector<std::pair<std::uint64_t, int>> edges;
    edges.reserve(3 * nf);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t a = m_.triangles[f][k], b = m_.triangles[f][(k + 1) % 3];
        edges.push_back({(std::min(a, b) << 32) | std::max(a, b), static_cast<int>(f)});
      }
    std::sort(edges.begin(), edges.end());
    neighbours_.assign(nf, {-1, -1, -1});
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].first == edges[i].first) ++j;
      if (j - i > 2)
        throw std::invalid_argument("base: non-manifold edge (" + std::to_string(edges[i].first >> 32) + ", " +
                                    std::to_string(edges[i].first & 0xffffffffu) + ") has more than two faces");
      if (j - i == 2) link(edges[i].second, edges[i + 1].second), link(edges[i + 1].second, edges[i].second);
      i = j;
    }
  }

  // Charts grown breadth first from the lowest unassigned face, taking neighbours whose normal is within the bound
  // of the seed's (faces without area join any chart).
  std::vector<std::vector<int>> grow() const {
    std::vector<char> taken(m_.triangle_count(), 0);
    std::vector<std::vector<int>> charts;
    for (std::size_t seed = 0; seed < m_.triangle_count(); ++seed) {
      if (taken[seed]) continue;
      const glm::dvec3 axis = normal_[seed];
      std::vector<int> faces{static_cast<int>(seed)};
      taken[seed] = 1;
      for (std::size_t q = 0; q < faces.size(); ++q)
        for (int g : neighbours_[static_cast<std::size_t>(faces[q])]) {
          if (g < 0 || taken[static_cast<std::size_t>(g)]) continue;
          const glm::dvec3& n = normal_[static_cast<std::size_t>(g)];
          if (axis != glm::dvec3(0.0) && n != glm::dvec3(0.0) && glm::dot(n, axis) < cos_max_) continue;
          taken[static_cast<std::size_t>(g)] = 1;
          faces.push_back(g);
        }
      charts.push_back(std::move(faces));
    }
    return charts;
  }

  // The connected pieces of `faces` (breadth first, each in `faces`' relative order).
  std::vector<std::vector<int>> components(const std::vector<int>& faces) const {
    std::vector<int> rank(m_.triangle_count(), -1);
    for (std::size_t i = 0; i < faces.size(); ++i) rank[static_cast<std::size_t>(faces[i])] = static_cast<int>(i);
    std::vector<char> seen(faces.size(), 0);
    std::vector<std::vector<int>> out;
    for (std::size_t s = 0; s < faces.size(); ++s) {
      if (seen[s]) continue;
      std::vector<int> piece{faces[s]};
      seen[s] = 1;
      for (std::size_t q = 0; q < piece.size(); ++q)
        for (int g : neighbours_[static_cast<std::size_t>(piece[q])]) {
          const int r = g < 0 ? -1 : rank[static_cast<std::size_t>(g)];
          if (r < 0 || seen[static_cast<std::size_t>(r)]) continue;
          seen[static_cast<std::size_t>(r)] = 1;
          piece.push_back(g);
        }
      out.push_back(std::move(piece));
    }
    return out;
  }

  // LSCM of a chart that is a topological disk (one border loop, Euler characteristic 1, manifold vertices), every
  // triangle with area keeping a positive orientation; nullopt otherwise (the caller splits the chart).
  std::optional<std::vector<glm::dvec2>> flatten(const std::vector<int>& faces) const {
    if (faces.size() == 1) return flat_triangle(faces.front());
    std::vector<int> local(m_.vertex_count(), -1);
    std::vector<std::uint32_t> verts;
    SurfaceMesh sm;
    std::vector<SurfaceMesh::Vertex_index> vi;
    for (int f : faces)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = m_.triangles[static_cast<std::size_t>(f)][k];
        if (local[v] >= 0) continue;
        local[v] = static_cast<int>(verts.size());
        verts.push_back(v);
        const glm::dvec3& p = m_.positions[v];
        vi.push_back(sm.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
      }
    for (int f : faces) {
      const glm::uvec3 t = m_.triangles[static_cast<std::size_t>(f)];
      if (sm.add_face(vi[static_cast<std::size_t>(local[t[0]])], vi[static_cast<std::size_t>(local[t[1]])],
                      vi[static_cast<std::size_t>(local[t[2]])]) == SurfaceMesh::null_face())
        return std::nullopt;  // a non-manifold vertex or edge within the chart
    }
    // A disk: χ = V − E + F = 1 and one border loop.
    const long chi = static_cast<long>(sm.number_of_vertices()) - static_cast<long>(sm.number_of_edges()) +
                     static_cast<long>(sm.number_of_faces());
    if (chi != 1) return std::nullopt;
    SurfaceMesh::Halfedge_index border;
    std::size_t border_halfedges = 0;
    for (SurfaceMesh::Halfedge_index h : sm.halfedges())
      if (sm.is_border(h)) {
        if (border_halfedges++ == 0) border = h;
      }
    if (border_halfedges == 0) return std::nullopt;
    std::size_t loop = 0;
    for (SurfaceMesh::Halfedge_index h : CGAL::halfedges_around_face(border, sm)) (void)h, ++loop;
    if (loop != border_halfedges) return std::nullopt;
    auto uv = sm.add_property_map<SurfaceMesh::Vertex_index, Kernel::Point_2>("v:uv").first;
    if (SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), border, uv) != SMP::OK) return std::nullopt;
    std::vector<glm::dvec2> corners;
    corners.reserve(3 * faces.size());
    double total = 0.0;
    for (int f : faces)
      for (int k = 0; k < 3; ++k) {
        const Kernel::Point_2 q = uv[vi[static_cast<std::size_t>(local[m_.triangles[static_cast<std::size_t>(f)][k]])]];
        if (!std::isfinite(q.x()) || !std::isfinite(q.y())) return std::nullopt;
        corners.push_back({q.x(), q.y()});
      }
    for (std::size_t i = 0; i < faces.size(); ++i)
      total += signed_area(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]);
    if (total < 0.0)
      for (glm::dvec2& c : corners) c.x = -c.x;  // a mirrored solution: the orientation is free
    // Every triangle with world area keeps a positive uv area (relative floor against round-off).
    const double floor = 1e-12 * std::abs(total);
    for (std::size_t i = 0; i < faces.size(); ++i)
      if (area_[static_cast<std::size_t>(faces[i])] > 0.0 &&
          !(signed_area(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]) > floor))
        return std::nullopt;
    return corners;
  }

  const TriMesh& mesh() const { return m_; }
  double area(int f) const { return area_[static_cast<std::size_t>(f)]; }

 private:
  void link(int f, int g) {
    for (int& n : neighbours_[static_cast<std::size_t>(f)])
      if (n < 0) {
        n = g;
        return;
      }
  }

  // One triangle laid flat with its edge lengths (vertex 0 at the origin, edge 0→1 along +u).
  std::vector<glm::dvec2> flat_triangle(int f) const {
    const glm::uvec3 t = m_.triangles[static_cast<std::size_t>(f)];
    const glm::dvec3 e1 = m_.positions[t[1]] - m_.positions[t[0]], e2 = m_.positions[t[2]] - m_.positions[t[0]];
    const double l1 = glm::length(e1);
    const double x = l1 > 0.0 ? glm::dot(e1, e2) / l1 : 0.0;
    const double y = l1 > 0.0 ? glm::length(glm::cross(e1, e2)) / l1 : 0.0;
    return {{0.0, 0.0}, {l1, 0.0}, {x, y}};
  }

  const TriMesh& m_;
  double cos_max_;
  std::vector<glm::dvec3> normal_;
  std::vector<double> area_;
  std::vector<std::array<int, 3>> neighbours_;
};

// Refuses a normal bound outside (0°, 90°], a mesh without triangles, a triangle index ≥ #V and a non-finite position.
void check_auto_uv_input(const TriMesh& mesh, double max_normal_deg) {
  if (!(max_normal_deg > 0.0 && max_normal_deg <= 90.0))
    throw std::invalid_argument("base: max_normal_deg must be in (0, 90], got " + std::to_string(max_normal_deg));
  if (mesh.triangles.empty()) throw std::invalid_argument("base: the mesh has no triangles");
  for (const glm::uvec3& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] >= mesh.vertex_count()) throw std::invalid_argument("base: a triangle index ≥ #V");
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::dvec3& p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("base: non-finite position at vertex " + std::to_string(v));
  }
}

// Flattens every grown chart; one that is no disk or flips is halved (growth order) and its pieces queued again.
// Adds the halvings to `splits`.
std::vector<Chart> flatten_auto_uv_charts(const Unwrapper& unwrap, std::size_t& splits) {
  std::deque<std::vector<int>> queue;
  for (auto& c : unwrap.grow()) queue.push_back(std::move(c));
  std::vector<Chart> charts;
  while (!queue.empty()) {
    std::vector<int> faces = std::move(queue.front());
    queue.pop_front();
    if (auto uv = unwrap.flatten(faces)) {
      charts.push_back({std::move(faces), std::move(*uv)});
      continue;
    }
    ++splits;
    const std::size_t half = faces.size() / 2;
    const std::vector<int> first(faces.begin(), faces.begin() + static_cast<long>(half)),
        second(faces.begin() + static_cast<long>(half), faces.end());
    for (const std::vector<int>* part : {&first, &second})
      for (auto& piece : unwrap.components(*part)) queue.push_back(std::move(piece));
  }
  return charts;
}

// Even texel density: every chart scaled so its uv area equals its world area, moved to its box's origin (Chart::hi:
// the box's size). Returns the total box area (world units²).
double scale_auto_uv_charts(std::vector<Chart>& charts, const Unwrapper& unwrap) {
  double box_area = 0.0;
  for (Chart& c : charts) {
    double world = 0.0, uv = 0.0;
    for (std::size_t i = 0; i < c.faces.size(); ++i) {
      world += unwrap.area(c.faces[i]);
      uv += signed_area(c.corner_uv[3 * i], c.corner_uv[3 * i + 1], c.corner_uv[3 * i + 2]);
    }
    const double s = uv > 0.0 && world > 0.0 ? std::sqrt(world / uv) : 1.0;
    glm::dvec2 lo(1e300), hi(-1e300);
    for (glm::dvec2& p : c.corner_uv) p *= s, lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (glm::dvec2& p : c.corner_uv) p -= lo;
    c.hi = hi - lo;
    box_area += std::max(c.hi.x, 1e-300) * std::max(c.hi.y, 1e-300);
  }
  return box_area;
}

// Shelf packing, tallest first (ties: chart order), shelves about as wide as the square of the total box area, with
// gaps of kGapFactor × √`box_area`: sets each chart's offset (Chart::lo). Returns the scale that maps the packing into
// [0,1]².
double pack_auto_uv_charts(std::vector<Chart>& charts, double box_area) {
  const double gap = kGapFactor * std::sqrt(box_area);
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return charts[a].hi.y > charts[b].hi.y; });
  double padded = 0.0;
  for (const Chart& c : charts) padded += (c.hi.x + gap) * (c.hi.y + gap);
  const double width = std::sqrt(padded);
  glm::dvec2 cursor(gap), extent(0.0);
  double shelf = 0.0;
  for (std::size_t i : order) {
    Chart& c = charts[i];
    if (cursor.x > gap && cursor.x + c.hi.x > width) cursor = {gap, cursor.y + shelf + gap}, shelf = 0.0;
    c.lo = cursor;
    shelf = std::max(shelf, c.hi.y);
    extent = glm::max(extent, cursor + c.hi);
    cursor.x += c.hi.x + gap;
  }
  return 1.0 / (std::max(extent.x, extent.y) + gap);
}

// The split mesh: chart by chart, each chart's vertices in first-use order, uv = (chart offset + corner uv) × `scale`;
// the normals `mesh`'s own, or its area-weighted vertex normals when it has none.
TriMesh auto_uv_split_mesh(const TriMesh& mesh, const std::vector<Chart>& charts, double scale) {
  std::vector<glm::dvec3> normals = mesh.normals;
  if (normals.size() != mesh.vertex_count()) {
    TriMesh with_normals = mesh;
    compute_vertex_normals(with_normals);
    normals = std::move(with_normals.normals);
  }
  TriMesh out;
  out.triangles.resize(mesh.triangle_count());
  std::vector<int> local(mesh.vertex_count(), -1);
  for (const Chart& c : charts) {
    std::vector<std::uint32_t> used;
    for (std::size_t i = 0; i < c.faces.size(); ++i) {
      const std::size_t f = static_cast<std::size_t>(c.faces[i]);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[f][k];
        if (local[v] < 0) {
          local[v] = static_cast<int>(out.positions.size());
          used.push_back(v);
          out.positions.push_back(mesh.positions[v]);
          out.normals.push_back(normals[v]);
          out.uvs.push_back((c.lo + c.corner_uv[3 * i + k]) * scale);
        }
        out.triangles[f][k] = static_cast<unsigned>(local[v]);
      }
    }
    for (std::uint32_t v : used) local[v] = -1;
  }
  return out;
}

// Area distortion of `out`: σ = uv area / world area per triangle against the mean σ̄ (uv total / world total), into
// st.area_distortion (max ÷ min) and st.area_distortion_p95 (between the area-weighted 2.5th and 97.5th
// percentiles); both left as they are when no triangle has area.
void measure_auto_uv_distortion(const TriMesh& out, DdmAutoUvStats& st) {
  std::vector<std::pair<double, double>> sigma;  // (σ/σ̄, world area)
  double world_total = 0.0, uv_total = 0.0;
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    const glm::uvec3 t = out.triangles[f];
    world_total += world_area(out, f);
    uv_total += signed_area(out.uvs[t[0]], out.uvs[t[1]], out.uvs[t[2]]);
  }
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    const glm::uvec3 t = out.triangles[f];
    const double w = world_area(out, f);
    if (w > 1e-12 * world_total)
      sigma.push_back({signed_area(out.uvs[t[0]], out.uvs[t[1]], out.uvs[t[2]]) / w * world_total / uv_total, w});
  }
  std::sort(sigma.begin(), sigma.end());
  if (sigma.empty()) return;
  st.area_distortion = sigma.back().first / sigma.front().first;
  double lo = sigma.front().first, hi = sigma.back().first, acc = 0.0, total = 0.0;
  for (const auto& s : sigma) total += s.second;
  bool lo_set = false;
  for (const auto& s : sigma) {
    acc += s.second;
    if (!lo_set && acc >= 0.025 * total) lo = s.first, lo_set = true;
    if (acc >= 0.975 * total) {
      hi = s.first;
      break;
    }
  }
  st.area_distortion_p95 = hi / lo;
}

}  // namespace

TriMesh ddm_auto_uv(const TriMesh& mesh, DdmAutoUvStats* stats, double max_normal_deg) {
  const auto t0 = std::chrono::steady_clock::now();
  check_auto_uv_input(mesh, max_normal_deg);
  const Unwrapper unwrap(mesh, max_normal_deg);
  DdmAutoUvStats st;
  std::vector<Chart> charts = flatten_auto_uv_charts(unwrap, st.splits);
  const double box_area = scale_auto_uv_charts(charts, unwrap);
  const double scale = pack_auto_uv_charts(charts, box_area);
  TriMesh out = auto_uv_split_mesh(mesh, charts, scale);
  measure_auto_uv_distortion(out, st);
  st.charts = charts.size();
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (stats) *stats = st;
  return out;
}

}  // namespace trispline::core
