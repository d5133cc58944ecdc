// Test patches shared by the DDM tests: a flat bilinear patch and a bicubic Bézier bump.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/spline/bspline_surface.h"

namespace trispline::core::test {

// S(u,v) = (a·u, b·v, 0): a flat bilinear patch (degree 1), normal +z.
inline BSplineSurface<glm::dvec3> flat_patch(double a, double b) {
  const KnotVector k(2, {0, 0, 1, 1});
  return BSplineSurface<glm::dvec3>(k, k, {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {a, b, 0}});
}

// A bicubic Bézier bump over [0,2]² (normal +z-ish, curved both ways).
inline BSplineSurface<glm::dvec3> bump_patch() {
  const KnotVector k(4, {0, 0, 0, 0, 1, 1, 1, 1});
  std::vector<glm::dvec3> cps;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double z = (i == 1 || i == 2) && (j == 1 || j == 2) ? 0.8 : (i == 0 || j == 0 ? -0.2 : 0.1);
      cps.push_back({2.0 * i / 3.0, 2.0 * j / 3.0, z});
    }
  return BSplineSurface<glm::dvec3>(k, k, cps);
}

}  // namespace trispline::core::test
