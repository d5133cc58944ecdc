// Shared helpers of the GLSL FFD tests: random control lattices of every knot type, error measures against the CPU
// double reference, and a deformed scene object.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/ffd/ffd.h"
#include "core/ffd/ffd_packed.h"
#include "core/scene/scene.h"
#include "tests/core/ffd/ffd_test_util.h"

namespace trispline::gpu::test {

// The knot vector families of the CPU FFD tests (tests/core/ffd/ffd_test_util.h), with their names.
using KnotType = core::test::KnotKind;
inline const char* to_string(KnotType t) { return core::test::name_of(t); }

// Clamped knot vector on [0,1] with `count` controls and random interior knots (one of them doubled when there
// are at least two), so spans differ in length and one is empty.
inline core::KnotVector nonuniform_clamped(int order, int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> uni(0.05, 0.95);
  const int interior = count - order;
  std::vector<double> in;
  for (int i = 0; i < interior; ++i) in.push_back(uni(rng));
  std::sort(in.begin(), in.end());
  if (interior >= 2) in[1] = in[0];  // a double knot
  std::vector<double> k(std::size_t(order), 0.0);
  k.insert(k.end(), in.begin(), in.end());
  k.insert(k.end(), std::size_t(order), 1.0);
  return core::KnotVector(order, std::move(k));
}

inline core::KnotVector knots_for(KnotType type, int axis, int order, int count, std::mt19937& rng) {
  switch (type) {
    case KnotType::clamped_uniform:
      return core::KnotVector::clamped_uniform(order, count);
    case KnotType::floating_uniform:
      return core::KnotVector::uniform(order, count);
    case KnotType::periodic_u:
      return axis == 0 ? core::KnotVector::periodic_uniform(order, count)
                       : core::KnotVector::clamped_uniform(order, count);
    default:
      return nonuniform_clamped(order, count, rng);
  }
}

// Random lattice over the box [-1,1]×[-0.5,0.5]×[-0.75,0.75]: a grid (a ring around the y axis on a periodic u
// axis) jittered by ±20 % of the spacing, so the map stays regular (normals well defined) but every control differs.
// counts: controls per axis (the period on a periodic axis); 0 = random (order..order+2, period 5..7).
inline core::TrivariateBSpline<glm::dvec3> random_box_lattice(KnotType type, glm::ivec3 orders, unsigned seed,
                                                              glm::ivec3 counts = glm::ivec3(0)) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> extra(0, 2);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  core::KnotVector kv[3] = {core::KnotVector::clamped_uniform(2, 2), core::KnotVector::clamped_uniform(2, 2),
                            core::KnotVector::clamped_uniform(2, 2)};
  for (int a = 0; a < 3; ++a) {
    const bool periodic = type == KnotType::periodic_u && a == 0;
    const int count = counts[a] > 0 ? counts[a] : periodic ? 5 + extra(rng) : orders[a] + extra(rng);
    kv[a] = knots_for(type, a, orders[a], count, rng);
  }
  const glm::ivec3 n(kv[0].stored_control_count(), kv[1].stored_control_count(), kv[2].stored_control_count());
  const glm::dvec3 size(2.0, 1.0, 1.5);
  std::vector<glm::dvec3> cps;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::dvec3 g(double(i) / std::max(n.x - 1, 1), double(j) / std::max(n.y - 1, 1),
                           double(k) / std::max(n.z - 1, 1));
        glm::dvec3 p = (g - 0.5) * size;
        if (type == KnotType::periodic_u) {  // ring: u goes around the y axis, w outwards
          const double phi = 2.0 * M_PI * double(i) / n.x, r = 1.0 + 0.5 * g.z;
          p = glm::dvec3(r * std::cos(phi), p.y, r * std::sin(phi));
        }
        const glm::dvec3 spacing = size / glm::dvec3(glm::max(n - 1, glm::ivec3(1)));
        cps.push_back(p + spacing * glm::dvec3(jitter(rng), jitter(rng), jitter(rng)));
      }
  return core::TrivariateBSpline<glm::dvec3>(kv[0], kv[1], kv[2], std::move(cps));
}

// A non-trivial embedding (scaled, rotated, offset) and random parameters (slightly outside [0,1]³ on clamped
// axes, to exercise clamping) with random unit rest normals.
inline core::Embedding test_embedding() {
  core::Embedding e;
  e.linear = glm::dmat3(0.8, 0.1, 0.0, -0.2, 0.9, 0.1, 0.05, 0.0, 1.3);
  e.offset = glm::dvec3(0.5, 0.5, 0.4);
  return e;
}
inline void random_vertices(int n, unsigned seed, std::vector<glm::dvec3>& params, std::vector<glm::dvec3>& normals) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-0.03, 1.03);
  std::normal_distribution<double> gauss;
  params.clear();
  normals.clear();
  for (int i = 0; i < n; ++i) {
    params.push_back({uni(rng), uni(rng), uni(rng)});
    glm::dvec3 d(gauss(rng), gauss(rng), gauss(rng));
    normals.push_back(glm::normalize(d + glm::dvec3(1e-3)));
  }
}

// Largest position error / largest normal angle (radians) of `pos`/`nrm` against the reference.
struct FfdErrors {
  double position = 0.0, normal_rad = 0.0;
  std::size_t worst = 0;
};
inline FfdErrors ffd_errors(const std::vector<glm::dvec3>& ref_pos, const std::vector<glm::dvec3>& ref_nrm,
                            const std::vector<glm::dvec3>& pos, const std::vector<glm::dvec3>& nrm) {
  FfdErrors e;
  for (std::size_t i = 0; i < ref_pos.size() && i < pos.size(); ++i) {
    const double d = glm::length(ref_pos[i] - pos[i]);
    if (!(d <= e.position)) {
      e.position = std::isnan(d) ? 1e30 : d;
      e.worst = i;
    }
    if (i < ref_nrm.size() && i < nrm.size()) {
      const double a = std::atan2(glm::length(glm::cross(ref_nrm[i], nrm[i])), glm::dot(ref_nrm[i], nrm[i]));
      e.normal_rad = std::max(e.normal_rad, std::isnan(a) ? 1e30 : a);
    }
  }
  return e;
}

inline double lattice_diagonal(const core::TrivariateBSpline<glm::dvec3>& F) {
  core::Aabb b;
  for (const glm::dvec3& p : F.control_points()) b.extend(p);
  return b.diagonal();
}

}  // namespace trispline::gpu::test
