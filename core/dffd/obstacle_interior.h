// trispline::core::ObstacleInterior — which points lie inside closed obstacle meshes, and how deep: the clearance
// check of a global DFFD (seed §6.3.1 splits an object around obstacles; no vertex may stay inside one).
//
// Inside is decided by CGAL's Side_of_triangle_mesh (ray parity on an AABB tree, exact predicates), depth by the AABB
// tree's closest point. A mesh counts only when it bounds a volume: after welding equal positions (primitives repeat
// a corner per face) it must be a closed, manifold triangle mesh; other meshes are listed as unchecked.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct ObstacleIntrusion {
  std::size_t inside = 0;         // points inside some obstacle
  double max_depth = 0.0;         // world units: the largest distance from such a point to its obstacle's surface
  std::string deepest_obstacle;   // the obstacle holding the deepest point ("" when none)
  glm::dvec3 deepest_point{0.0};  // world units
};

class ObstacleInterior {
 public:
  // `names` and `world_meshes` (world units) in the same order. Never throws on a mesh that is not closed (it is
  // listed by unchecked()); throws std::invalid_argument when the sizes differ or a position is not finite.
  ObstacleInterior(const std::vector<std::string>& names, const std::vector<const TriMesh*>& world_meshes);
  ~ObstacleInterior();
  ObstacleInterior(const ObstacleInterior&) = delete;
  ObstacleInterior& operator=(const ObstacleInterior&) = delete;

  // Names of the obstacles that do not bound a volume (open or non-manifold after welding): nothing is inside them.
  const std::vector<std::string>& unchecked() const { return unchecked_; }

  // The points (#P × 3, world units) inside an obstacle. Deterministic; points on a surface are not inside.
  ObstacleIntrusion intrusion(const std::vector<glm::dvec3>& points) const;

 private:
  struct Solid;
  std::vector<std::unique_ptr<Solid>> solids_;
  std::vector<std::string> unchecked_;
};

}  // namespace trispline::core
