// Scenes for the placement tests: generated terrains with analytic distance functions, a tessellated box object
// and a top-down camera.
#pragma once

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/mesh/uv_sphere.h"
#include "core/placement/sketch_placement.h"
#include "core/raycast/ray_caster.h"
#include "tests/test_shapes.h"

namespace trispline::core::test {

// Height field y = h(x, z) over [-half, half]² with n×n cells, CCW seen from above (+y).
inline TriMesh height_field(double half, int n, const std::function<double(double, double)>& h) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -half + 2.0 * half * i / n, z = -half + 2.0 * half * j / n;
      m.positions.emplace_back(x, h(x, z), z);
    }
  auto id = [n](int i, int j) { return static_cast<unsigned>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.emplace_back(id(i, j), id(i, j + 1), id(i + 1, j + 1));
      m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i + 1, j));
    }
  return m;
}

inline double bumps(double x, double z) { return 0.15 * std::sin(1.5 * x) * std::cos(1.2 * z); }

// Box [0,L]×[0,H]×[0,D] translated by `at`, every face an n×n grid (CCW outward; edge vertices duplicated per face).
inline TriMesh tessellated_box(glm::dvec3 size, glm::dvec3 at, int n) {
  TriMesh m;
  auto face = [&](glm::dvec3 o, glm::dvec3 a, glm::dvec3 b) {  // a × b points outward
    const unsigned base = static_cast<unsigned>(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.positions.push_back(at + o + a * (double(i) / n) + b * (double(j) / n));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const unsigned v0 = base + i + (n + 1) * j, v1 = v0 + 1, v2 = v0 + (n + 1), v3 = v2 + 1;
        m.triangles.emplace_back(v0, v1, v3);
        m.triangles.emplace_back(v0, v3, v2);
      }
  };
  const glm::dvec3 X(size.x, 0, 0), Y(0, size.y, 0), Z(0, 0, size.z), O(0.0);
  face(O, X, Z);  // bottom (normal −y)
  face(Y, Z, X);  // top (+y)
  face(O, Y, X);  // back (−z)
  face(Z, X, Y);  // front (+z)
  face(O, Z, Y);  // left (−x)
  face(X, Y, Z);  // right (+x)
  return m;
}

inline Camera top_down_camera() { return trispline::test::top_camera(6.0, 45.0, {1280, 720}); }

inline RayCaster caster_for(const TriMesh& scene) {
  RayCaster rc;
  rc.add_mesh(scene);
  rc.commit();
  return rc;
}

inline std::vector<glm::dvec2> straight_stroke() { return {{400, 360}, {560, 362}, {720, 358}, {880, 360}}; }

// 120° arc of radius 250 px bulging up on screen, drawn left to right (from 150° to 30°).
inline std::vector<glm::dvec2> curved_stroke() {
  std::vector<glm::dvec2> s;
  for (int k = 0; k <= 40; ++k) {
    const double a = std::numbers::pi * (150.0 - 120.0 * k / 40.0) / 180.0;
    s.emplace_back(640.0 + 250.0 * std::cos(a), 560.0 - 250.0 * std::sin(a));
  }
  return s;
}

inline SketchPlacementParams default_params(std::vector<glm::dvec2> stroke) {
  SketchPlacementParams p;
  p.stroke_px = std::move(stroke);
  p.camera = top_down_camera();
  p.half_width = 0.3;
  p.height = 0.4;
  p.samples_u = 40;
  p.samples_v = 9;
  p.order = {4, 4, 2};
  p.controls = {10, 5, 2};
  p.axes = {0, 1};
  return p;
}

}  // namespace trispline::core::test
