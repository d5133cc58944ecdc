// Analytic volumes of the iso-surface ray casting tests (core and GLSL): signed distance fields sampled on a grid
// with an oblique, anisotropic index → world map, positive inside (like CT densities above an iso-level), so the
// iso-surface D = 0 approximates a known surface and −∇D is its outward normal.
#pragma once

#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/volume/scalar_volume.h"

namespace trispline::test {

// index → world (millimetres): scale by `spacing`, rotate by `angle_deg` about `axis`, translate by `origin`.
inline glm::dmat4 oblique_index_to_world(const glm::dvec3& spacing, double angle_deg, const glm::dvec3& axis,
                                         const glm::dvec3& origin) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), origin);
  if (angle_deg != 0.0) m = glm::rotate(m, glm::radians(angle_deg), glm::normalize(axis));
  return glm::scale(m, spacing);
}

// `field` (world millimetres → value) sampled at every voxel of a dims grid placed by index_to_world.
inline core::ScalarVolume sample_volume(const glm::ivec3& dims, const glm::dmat4& index_to_world,
                                        const std::function<double(const glm::dvec3&)>& field) {
  core::ScalarVolume v;
  v.dims = {dims.x, dims.y, dims.z};
  v.index_to_world = index_to_world;
  v.values.resize(std::size_t(dims.x) * dims.y * dims.z);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) v.values[v.index(i, j, k)] = float(field(v.world(glm::dvec3(i, j, k))));
  v.source = "analytic";
  return v;
}

// A sphere: radius minus the distance to the centre.
struct SphereField {
  glm::dvec3 center;
  double radius;
  double operator()(const glm::dvec3& p) const { return radius - glm::length(p - center); }
};

// A torus about the axis `axis` (unit) through `center`: tube radius minus the distance to the core circle of radius
// `major`.
struct TorusField {
  glm::dvec3 center;
  glm::dvec3 axis;
  double major, minor;
  // The nearest core-circle point to p (p off the axis).
  glm::dvec3 core_point(const glm::dvec3& p) const {
    const glm::dvec3 q = p - center;
    const glm::dvec3 radial = q - glm::dot(q, axis) * axis;
    return center + major * glm::normalize(radial);
  }
  double operator()(const glm::dvec3& p) const { return minor - glm::length(p - core_point(p)); }
  glm::dvec3 outward_normal(const glm::dvec3& p) const { return glm::normalize(p - core_point(p)); }
};

// The sphere case: 40³ voxels of 0.8 × 1.0 × 1.2 mm, rotated 20° and offset; radius 12 mm at the box centre.
struct SphereVolume {
  SphereField field;
  core::ScalarVolume volume;
};
inline SphereVolume sphere_volume(const glm::ivec3& dims = {40, 40, 40}) {
  const glm::dmat4 m = oblique_index_to_world({0.8, 1.0, 1.2}, 20.0, {1.0, 2.0, 0.5}, {-15.0, 7.0, 22.0});
  const glm::dvec3 center = glm::dvec3(m * glm::dvec4(0.5 * glm::dvec3(dims - 1), 1.0));
  SphereField f{center, 12.0};
  return {f, sample_volume(dims, m, f)};
}

// The torus case: 48 × 48 × 24 voxels of 0.9 × 0.9 × 1.0 mm with an offset and a 15° tilt; major radius 13 mm,
// minor 4.5 mm, axis = the grid's z axis in world space.
struct TorusVolume {
  TorusField field;
  core::ScalarVolume volume;
};
inline TorusVolume torus_volume() {
  const glm::ivec3 dims(48, 48, 24);
  const glm::dmat4 m = oblique_index_to_world({0.9, 0.9, 1.0}, 15.0, {1.0, 0.0, 0.0}, {4.0, -3.0, 10.0});
  const glm::dvec3 center = glm::dvec3(m * glm::dvec4(0.5 * glm::dvec3(dims - 1), 1.0));
  const glm::dvec3 axis = glm::normalize(glm::dmat3(m) * glm::dvec3(0.0, 0.0, 1.0));
  TorusField f{center, axis, 13.0, 4.5};
  return {f, sample_volume(dims, m, f)};
}

}  // namespace trispline::test
