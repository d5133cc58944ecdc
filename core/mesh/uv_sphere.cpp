// UV spheres. See uv_sphere.h.
#include "core/mesh/uv_sphere.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/mesh/mesh_io.h"

namespace trispline::core {

TriMesh make_uv_sphere(double radius, int rings, int segments, SpherePhi phi, SphereNormals normals) {
  if (rings < 2 || segments < 3) throw std::invalid_argument("make_uv_sphere: need rings >= 2 and segments >= 3");
  const bool plus_z = phi == SpherePhi::toward_plus_z;
  TriMesh m;
  const double pi = std::numbers::pi;
  m.positions.emplace_back(0.0, radius, 0.0);  // north pole
  for (int r = 1; r < rings; ++r) {
    const double th = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double ph = 2.0 * pi * s / segments;
      const double z = plus_z ? radius * std::sin(th) * std::sin(ph) : -radius * std::sin(th) * std::sin(ph);
      m.positions.emplace_back(radius * std::sin(th) * std::cos(ph), radius * std::cos(th), z);
    }
  }
  m.positions.emplace_back(0.0, -radius, 0.0);  // south pole
  const unsigned south = static_cast<unsigned>(m.positions.size() - 1);
  auto ring = [&](int r, int s) { return static_cast<unsigned>(1 + (r - 1) * segments + (s % segments)); };
  // (a, b, c) CCW seen from outside for toward_minus_z; the mirror image winds (a, c, b).
  auto tri = [&](unsigned a, unsigned b, unsigned c) {
    if (plus_z)
      m.triangles.emplace_back(a, c, b);
    else
      m.triangles.emplace_back(a, b, c);
  };
  for (int s = 0; s < segments; ++s) tri(0u, ring(1, s), ring(1, s + 1));
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      tri(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      tri(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  for (int s = 0; s < segments; ++s) tri(ring(rings - 1, s), south, ring(rings - 1, s + 1));
  if (normals == SphereNormals::radial) {
    m.normals.reserve(m.positions.size());
    for (const auto& p : m.positions) m.normals.push_back(p / radius);
  } else {
    compute_vertex_normals(m);
  }
  return m;
}

}  // namespace trispline::core
