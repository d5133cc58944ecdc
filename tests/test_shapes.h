// Named test shapes and cameras shared by the test folders (one definition each): closed tori, sphere objects, the
// top and front cameras.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "core/scene/primitives.h"
#include "core/scene/scene.h"

namespace trispline::test {

// Torus around z (R = 2, r = 0.7), closed, shared vertices (nu × nv of them); the plane x = 0 cuts it in two circles.
// With `normals` the exact unit normals are filled in.
inline core::TriMesh torus_mesh(int nu, int nv, bool normals = true) {
  core::TriMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double a = 2.0 * M_PI * i / nu, b = 2.0 * M_PI * j / nv;
      m.positions.push_back(
          {std::cos(a) * (2.0 + 0.7 * std::cos(b)), std::sin(a) * (2.0 + 0.7 * std::cos(b)), 0.7 * std::sin(b)});
      if (normals) m.normals.push_back({std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)});
    }
  auto id = [&](int i, int j) { return static_cast<unsigned>(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// The sphere primitive (radius 1, `slices` × `stacks`) as an evaluated object named `name` at `translate`.
inline core::SceneObject sphere_object(const std::string& name, int slices, int stacks, const glm::dvec3& translate) {
  core::SceneObject o;
  o.name = name;
  o.source = "primitive:sphere";
  o.rest_mesh = std::make_shared<const core::TriMesh>(core::make_sphere(slices, stacks));
  o.transform.translate = translate;
  o.refresh();
  return o;
}

// A camera looking straight down at the xz-plane from (0, `height`, 0), image up = −z; vertical field of view
// `fov_deg`, `viewport` pixels.
inline core::Camera top_camera(double height, double fov_deg, glm::ivec2 viewport) {
  core::Camera c;
  c.eye = {0.0, height, 0.0};
  c.target = {0.0, 0.0, 0.0};
  c.up = {0.0, 0.0, -1.0};
  c.fov_deg = fov_deg;
  c.viewport = viewport;
  return c;
}

// A camera on +z at `distance` looking at the origin, up = +y; vertical field of view `fov_deg`, `viewport` pixels.
inline core::Camera front_camera(double distance, double fov_deg, glm::ivec2 viewport) {
  core::Camera c;
  c.eye = {0.0, 0.0, distance};
  c.target = {0.0, 0.0, 0.0};
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = fov_deg;
  c.viewport = viewport;
  return c;
}

}  // namespace trispline::test
