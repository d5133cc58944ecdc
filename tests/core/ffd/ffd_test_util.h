// Shared helpers for the FFD tests: lattices (identity, bent, perturbed) and shapes.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "bench/seed_cube.h"
#include "core/ffd/ffd.h"
#include "core/mesh/uv_sphere.h"

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

// The seed's cube and its bend + twist (bench/seed_cube.h).
inline TriMesh cube12() { return seed_cube(); }
inline FfdBinding bent_twisted_binding(const TriMesh& mesh) { return seed_cube_bend_twist(mesh); }

}  // namespace trispline::core::test

namespace trispline::core::test {

// Knot vector families the float backends support (ffd_evaluator.h).
enum class KnotKind { clamped_uniform, floating_uniform, periodic_u, nonuniform_clamped };
inline const char* name_of(KnotKind k) {
  switch (k) {
    case KnotKind::clamped_uniform:
      return "clamped uniform";
    case KnotKind::floating_uniform:
      return "floating uniform";
    case KnotKind::periodic_u:
      return "periodic along u";
    case KnotKind::nonuniform_clamped:
      return "non-uniform clamped";
  }
  return "?";
}
inline constexpr KnotKind kAllKnotKinds[] = {KnotKind::clamped_uniform, KnotKind::floating_uniform,
                                             KnotKind::periodic_u, KnotKind::nonuniform_clamped};

// Knot vector of `kind` along `axis` (periodic only along u) with order + 2 stored controls (period 5 when
// periodic); non-uniform: interior knots graded by a power law.
inline KnotVector knots_of(KnotKind kind, int axis, int order) {
  switch (kind) {
    case KnotKind::clamped_uniform:
      return KnotVector::clamped_uniform(order, order + 2);
    case KnotKind::floating_uniform:
      return KnotVector::uniform(order, order + 2);
    case KnotKind::periodic_u:
      return axis == 0 ? KnotVector::periodic_uniform(order, 5) : KnotVector::clamped_uniform(order, order + 2);
    case KnotKind::nonuniform_clamped: {
      const int n = order + 3;
      std::vector<double> k(static_cast<std::size_t>(n + order));
      for (int i = 0; i < n + order; ++i)
        k[i] = i < order ? 0.0 : i >= n ? 1.0 : std::pow((i - order + 1.0) / (n - order + 1.0), 1.6 + 0.2 * axis);
      return KnotVector(order, std::move(k));
    }
  }
  return KnotVector::clamped_uniform(order, order);
}

// A random, orientation-preserving lattice: Greville abscissae (stored controls) mapped to a box
// [0,2]×[0,1]×[0,1.5] — or, along a periodic u, to a ring of radius 2 (u = angle, v = radial, w = height) — plus a
// uniform random displacement of ±20 % of a control spacing per coordinate.
inline TrivariateBSpline<glm::dvec3> random_lattice(KnotKind kind, glm::ivec3 orders, unsigned seed) {
  KnotVector k[3] = {knots_of(kind, 0, orders.x), knots_of(kind, 1, orders.y), knots_of(kind, 2, orders.z)};
  std::vector<double> g[3];
  for (int a = 0; a < 3; ++a) {
    g[a] = k[a].greville();
    g[a].resize(static_cast<std::size_t>(k[a].stored_control_count()));
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-0.2, 0.2);
  std::vector<glm::dvec3> cps;
  const bool ring = k[0].is_periodic();
  for (double w : g[2])
    for (double v : g[1])
      for (double u : g[0]) {
        glm::dvec3 p = ring ? glm::dvec3((2.0 + v) * std::cos(2.0 * 3.14159265358979 * u),
                                         (2.0 + v) * std::sin(2.0 * 3.14159265358979 * u), 1.5 * w)
                            : glm::dvec3(2.0 * u, v, 1.5 * w);
        const double cell = 1.0 / static_cast<double>(std::max({g[0].size(), g[1].size(), g[2].size()}));
        p += cell * glm::dvec3(uni(rng), uni(rng), uni(rng));
        cps.push_back(p);
      }
  return TrivariateBSpline<glm::dvec3>(k[0], k[1], k[2], std::move(cps));
}

// Deterministic random unit vectors.
inline std::vector<glm::dvec3> random_normals(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<glm::dvec3> v;
  while (v.size() < n) {
    const glm::dvec3 d(g(rng), g(rng), g(rng));
    if (glm::length(d) > 1e-3) v.push_back(glm::normalize(d));
  }
  return v;
}

// Largest angle (rad) between corresponding unit vectors; atan2 form, accurate near 0.
inline double max_angle(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    m = std::max(m, std::atan2(glm::length(glm::cross(a[i], b[i])), glm::dot(a[i], b[i])));
  return m;
}

// Largest position distance divided by the diagonal of the lattice's control-point bounding box.
inline double max_rel_error(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                            const TrivariateBSpline<glm::dvec3>& F) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) m = std::max(m, glm::length(a[i] - b[i]));
  return m / bounds_of(F.control_points()).diagonal();
}

}  // namespace trispline::core::test
