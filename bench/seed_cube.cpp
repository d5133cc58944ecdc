#include "bench/seed_cube.h"

#include <cmath>

namespace trispline::core {

namespace {

// Order-4 lattice of 5 controls per axis reproducing the identity over `mesh`'s bounding box: the Greville
// abscissae mapped back through the embedding (linear precision of clamped B-splines), params bound.
FfdBinding identity_binding(const TriMesh& mesh) {
  const Embedding e = embed_bounding_box(mesh.positions, {0, 1});
  const KnotVector k = KnotVector::clamped_uniform(4, 5);
  const std::vector<double> g = k.greville();
  const glm::dmat3 inv = glm::inverse(e.linear);
  std::vector<glm::dvec3> cps;
  for (double w : g)
    for (double v : g)
      for (double u : g) cps.push_back(inv * (glm::dvec3(u, v, w) - e.offset));
  return FfdBinding{TrivariateBSpline<glm::dvec3>(k, k, k, std::move(cps)), e, embed_points(e, mesh.positions)};
}

}  // namespace

TriMesh seed_cube() {
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  const unsigned q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  for (const auto& p : m.positions) m.normals.push_back(glm::normalize(p));
  return m;
}

FfdBinding seed_cube_bend_twist(const TriMesh& mesh) {
  FfdBinding b = identity_binding(mesh);
  for (glm::dvec3& p : b.lattice.control_points()) {
    const double R = 2.0, th = p.x / R, r = R + p.y, phi = 0.5 * p.x;
    const glm::dvec3 bent(r * std::sin(th), r * std::cos(th) - R, p.z);
    p = {bent.x, bent.y * std::cos(phi) - bent.z * std::sin(phi), bent.y * std::sin(phi) + bent.z * std::cos(phi)};
  }
  return b;
}

FfdBinding seed_cube_corner_pull(const TriMesh& mesh) {
  FfdBinding b = identity_binding(mesh);
  b.lattice.control_point(4, 4, 4) += glm::dvec3(0.6);
  return b;
}

}  // namespace trispline::core
