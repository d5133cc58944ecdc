// Shared helpers for the FFD tests: lattices (identity, bent, perturbed) and shapes.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "core/deform/ffd.h"
#include "core/deform/ffd_bench.h"

namespace trispline::core::test {

// Lattice whose control points are the Greville abscissae mapped back to world space through the embedding:
// F(E(x)) = x (linear precision of clamped B-splines).
inline TrivariateBSpline<glm::dvec3> identity_lattice(const Embedding& e, KnotVector ku, KnotVector kv, KnotVector kw) {
  const auto gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  const glm::dmat3 inv = glm::inverse(e.linear);
  std::vector<glm::dvec3> cps;
  for (double w : gw)
    for (double v : gv)
      for (double u : gu) cps.push_back(inv * (glm::dvec3(u, v, w) - e.offset));
  return TrivariateBSpline<glm::dvec3>(std::move(ku), std::move(kv), std::move(kw), std::move(cps));
}

// Identity lattice bent and twisted smoothly (a non-trivial, orientation-preserving deformation).
inline TrivariateBSpline<glm::dvec3> bent_lattice(const Embedding& e, KnotVector ku, KnotVector kv, KnotVector kw) {
  auto F = identity_lattice(e, ku, kv, kw);
  const auto gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  const glm::ivec3 c = F.control_counts();
  for (int k = 0; k < c.z; ++k)
    for (int j = 0; j < c.y; ++j)
      for (int i = 0; i < c.x; ++i) {
        glm::dvec3& p = F.control_point(i, j, k);
        const double u = gu[i], v = gv[j], w = gw[k];
        p.y += 0.4 * (u - 0.5) * (u - 0.5) + 0.1 * std::sin(3.0 * v);
        p.z += 0.15 * u * w;
        p.x += 0.1 * std::cos(2.0 * w) * v;
      }
  return F;
}

// Deterministic random points in a box.
inline std::vector<glm::dvec3> random_points(int n, glm::dvec3 lo, glm::dvec3 hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(lo + (hi - lo) * glm::dvec3(uni(rng), uni(rng), uni(rng)));
  return pts;
}

inline Aabb bounds_of(const std::vector<glm::dvec3>& pts) {
  Aabb b;
  for (const auto& p : pts) b.extend(p);
  return b;
}

}  // namespace trispline::core::test
