// Even–odd filling of nested planar loops by CGAL's constrained Delaunay triangulation. See planar_triangulation.h.
// The nesting-depth marking is the CGAL 2D Triangulations manual's "polygon with holes" example (mark_domains).
#include "core/mesh/planar_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <deque>

namespace trispline::core {
namespace {

struct VertexInfo {
  std::int64_t index = -1;  // the loops' vertex; -1 for a vertex CGAL made at a constraint crossing
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

}  // namespace

std::vector<std::array<std::uint32_t, 3>> triangulate_nested_loops(
    const std::vector<std::vector<std::uint32_t>>& loops, const std::function<glm::dvec2(std::uint32_t)>& point_of) {
  std::vector<std::uint32_t> verts;
  for (const auto& loop : loops) verts.insert(verts.end(), loop.begin(), loop.end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());

  // Points inserted in CGAL's spatial (Hilbert) order with the previous vertex as location hint, as CGAL's own
  // range insertion does (deterministic: spatial_sort shuffles with a fixed-seed rand48); a 2D duplicate maps to
  // the smallest index at that point.
  std::vector<K::Point_2> points(verts.size());
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const glm::dvec2 p = point_of(verts[i]);
    points[i] = K::Point_2(p.x, p.y);
  }
  std::vector<std::size_t> order(verts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Pmap = CGAL::Pointer_property_map<K::Point_2>::type;
  CGAL::spatial_sort(order.begin(), order.end(),
                     CGAL::Spatial_sort_traits_adapter_2<K, Pmap>(CGAL::make_property_map(points)));
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handle(verts.size());
  Cdt::Face_handle hint;
  for (std::size_t i : order) {
    const Cdt::Vertex_handle h = cdt.insert(points[i], hint);
    if (h->info().index < 0 || h->info().index > static_cast<std::int64_t>(verts[i])) h->info().index = verts[i];
    handle[i] = h;
    hint = h->face();
  }
  auto handle_of = [&](std::uint32_t v) {
    return handle[static_cast<std::size_t>(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin())];
  };
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Cdt::Vertex_handle ha = handle_of(loop[i]), hb = handle_of(loop[(i + 1) % loop.size()]);
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

}  // namespace trispline::core
