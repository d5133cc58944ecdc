// Shared by the silhouette tests: the visible points of an extraction, and how many of one set of points lie near
// another (a hash grid of cells `radius` wide).
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <tuple>
#include <vector>

#include "core/volume/silhouettes.h"

namespace trispline::core::test {

// The visible points of every polyline of `r`, millimetres.
inline std::vector<glm::dvec3> visible_points(const SilhouetteResult& r) {
  std::vector<glm::dvec3> out;
  for (const SilhouettePolyline& pl : r.polylines)
    for (std::size_t i = 0; i < pl.points.size(); ++i)
      if (pl.visible[i]) out.push_back(pl.points[i]);
  return out;
}

// The share of `points` within `radius` of some point of `of` (a grid of cells `radius` wide).
inline double covered(const std::vector<glm::dvec3>& points, const std::vector<glm::dvec3>& of, double radius) {
  std::map<std::tuple<int, int, int>, std::vector<glm::dvec3>> grid;
  auto key = [&](const glm::dvec3& p) {
    return std::make_tuple(int(std::floor(p.x / radius)), int(std::floor(p.y / radius)), int(std::floor(p.z / radius)));
  };
  for (const glm::dvec3& p : of) grid[key(p)].push_back(p);
  std::size_t near = 0;
  for (const glm::dvec3& p : points) {
    const auto [x, y, z] = key(p);
    bool found = false;
    for (int dz = -1; dz <= 1 && !found; ++dz)
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const auto it = grid.find({x + dx, y + dy, z + dz});
          if (it == grid.end()) continue;
          for (const glm::dvec3& q : it->second)
            if (glm::length(q - p) <= radius) {
              found = true;
              break;
            }
        }
    near += found;
  }
  return points.empty() ? 1.0 : double(near) / double(points.size());
}

}  // namespace trispline::core::test
