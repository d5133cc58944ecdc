// Point-in-solid for DFFD clearance: CGAL 5.5's Side_of_triangle_mesh and AABB tree on a Surface_mesh. See
// obstacle_interior.h.
#include "core/dffd/obstacle_interior.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

namespace trispline::core {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

// The mesh with equal positions welded, or nothing when it is not a closed manifold triangle mesh.
std::optional<Mesh> closed_mesh(const TriMesh& m) {
  Mesh out;
  std::map<std::tuple<double, double, double>, Mesh::Vertex_index> welded;
  std::vector<Mesh::Vertex_index> index(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3& p = m.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("an obstacle has a non-finite vertex position");
    auto [it, fresh] = welded.try_emplace({p.x, p.y, p.z}, Mesh::Vertex_index());
    if (fresh) it->second = out.add_vertex(Point(p.x, p.y, p.z));
    index[i] = it->second;
  }
  for (const glm::uvec3& t : m.triangles) {
    if (t.x >= index.size() || t.y >= index.size() || t.z >= index.size()) return std::nullopt;
    const auto a = index[t.x], b = index[t.y], c = index[t.z];
    if (a == b || b == c || a == c) continue;                             // a triangle welded to an edge bounds nothing
    if (out.add_face(a, b, c) == Mesh::null_face()) return std::nullopt;  // non-manifold
  }
  if (out.number_of_faces() == 0 || !CGAL::is_closed(out)) return std::nullopt;
  return out;
}

}  // namespace

struct ObstacleInterior::Solid {
  explicit Solid(std::string n, Mesh m)
      : name(std::move(n)), mesh(std::move(m)), tree(faces(mesh).first, faces(mesh).second, mesh), side(tree) {
    tree.accelerate_distance_queries();
  }
  std::string name;
  Mesh mesh;
  Tree tree;
  CGAL::Side_of_triangle_mesh<Mesh, K, CGAL::Default, Tree> side;
};

ObstacleInterior::ObstacleInterior(const std::vector<std::string>& names,
                                   const std::vector<const TriMesh*>& world_meshes) {
  if (names.size() != world_meshes.size()) throw std::invalid_argument("ObstacleInterior: one name per obstacle mesh");
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::optional<Mesh> m = world_meshes[i] ? closed_mesh(*world_meshes[i]) : std::nullopt;
    if (m)
      solids_.push_back(std::make_unique<Solid>(names[i], std::move(*m)));
    else
      unchecked_.push_back(names[i]);
  }
}

ObstacleInterior::~ObstacleInterior() = default;

ObstacleIntrusion ObstacleInterior::intrusion(const std::vector<glm::dvec3>& points) const {
  ObstacleIntrusion out;
  for (const glm::dvec3& x : points) {
    const Point p(x.x, x.y, x.z);
    for (const auto& s : solids_) {
      if (s->side(p) != CGAL::ON_BOUNDED_SIDE) continue;
      ++out.inside;
      const double depth = std::sqrt(s->tree.squared_distance(p));
      if (depth > out.max_depth || out.deepest_obstacle.empty())
        out.max_depth = depth, out.deepest_obstacle = s->name, out.deepest_point = x;
      break;
    }
  }
  return out;
}

}  // namespace trispline::core
