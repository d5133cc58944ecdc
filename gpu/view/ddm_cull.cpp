// Culling and thinning of live DDM layer instances on the CPU. See ddm_cull.h.
#include "gpu/view/ddm_cull.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>

#include "core/ddm/ddm_pn_maps.h"
#include "core/mesh/mesh_io.h"

namespace trispline::gpu {

// SplitMix64's finaliser of the index, its top 24 bits as a fraction.
float ddm_lod_rank(std::size_t instance) {
  const std::uint64_t k = instance;
  std::uint64_t z = k + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<float>(static_cast<double>(z >> 40) / static_cast<double>(std::uint64_t{1} << 24));
}

DdmInstanceBounds ddm_instance_bounds(const core::DdmLayer& layer) {
  DdmInstanceBounds b;
  if (!layer.mesh || !layer.maps || layer.animated() || layer.tiles.empty()) return b;
  const std::size_t n = layer.instances.size();
  std::vector<std::size_t> first(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const int t = layer.instances[k].tile;
    if (t < 0 || t >= static_cast<int>(layer.tiles.size())) return b;
    first[k + 1] = first[k] + layer.tiles[static_cast<std::size_t>(t)].mesh.vertex_count();
  }
  const core::TriMesh& mesh = *layer.mesh;
  if (mesh.vertex_count() != first.back()) return b;
  const double slack = 1e-4 * core::mesh_bounds(mesh).diagonal();
  const core::DdmMapsBase base(layer.maps);
  const glm::dvec2 centre = layer.transform.apply({0.5, 0.5});
  b.spheres.resize(n);
  b.normals.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    glm::dvec3 a(std::numeric_limits<double>::max()), z(-std::numeric_limits<double>::max());
    for (std::size_t v = first[k]; v < first[k + 1]; ++v)
      a = glm::min(a, mesh.positions[v]), z = glm::max(z, mesh.positions[v]);
    const glm::dvec3 c = first[k + 1] > first[k] ? 0.5 * (a + z) : glm::dvec3(0.0);
    double r2 = 0.0;
    for (std::size_t v = first[k]; v < first[k + 1]; ++v)
      r2 = std::max(r2, glm::dot(mesh.positions[v] - c, mesh.positions[v] - c));
    b.spheres[k] = glm::vec4(glm::vec3(c), static_cast<float>(std::sqrt(r2) * (1.0 + 1e-6) + slack));
    b.lo = k == 0 ? c - double(b.spheres[k].w) : glm::min(b.lo, c - double(b.spheres[k].w));
    b.hi = k == 0 ? c + double(b.spheres[k].w) : glm::max(b.hi, c + double(b.spheres[k].w));
    const core::DdmInstance& inst = layer.instances[k];
    const glm::dvec2 uv = inst.origin + inst.size * centre;  // time 0: no texture-space offset
    const glm::dvec3 nrm = base.eval(inst.chart, uv.x, uv.y).n;
    const double len = glm::length(nrm);
    b.normals[k] = len > 0.0 && std::isfinite(len) ? glm::vec3(nrm / len) : glm::vec3(0.0f);
  }
  return b;
}

std::array<glm::dvec4, 6> frustum_planes(const glm::dmat4& m) {
  // Rows of the matrix (GLM is column-major: m[col][row]).
  const glm::dvec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]), r1(m[0][1], m[1][1], m[2][1], m[3][1]),
      r2(m[0][2], m[1][2], m[2][2], m[3][2]), r3(m[0][3], m[1][3], m[2][3], m[3][3]);
  std::array<glm::dvec4, 6> p = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
  for (glm::dvec4& q : p) {
    const double len = glm::length(glm::dvec3(q));
    if (len > 0.0) q /= len;
  }
  return p;
}

DdmCuller::DdmCuller(const DdmInstanceBounds& bounds, const DdmCullView& view)
    : bounds_(bounds), view_(view), planes_(frustum_planes(view.view_proj)) {
  const glm::dmat3 linear(view.model);
  normal_matrix_ = glm::inverseTranspose(linear);
  scale_ = std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
  const glm::dvec3 eye = glm::dvec3(glm::inverse(view.model) * glm::dvec4(view.eye, 1.0));
  const bool inside = glm::all(glm::greaterThanEqual(eye, bounds.lo)) && glm::all(glm::lessThanEqual(eye, bounds.hi));
  margin_ = view.backface_margin_deg < 0.0 || inside ? -1.0 : glm::radians(view.backface_margin_deg);
}

DdmCullReason DdmCuller::test(std::size_t k) const {
  const glm::vec4 s = bounds_.spheres[k];
  const glm::dvec3 c = glm::dvec3(view_.model * glm::dvec4(s.x, s.y, s.z, 1.0));
  const double r = s.w * scale_;
  if (view_.frustum)
    for (const glm::dvec4& p : planes_)
      if (glm::dot(glm::dvec3(p), c) + p.w < -r) return DdmCullReason::outside;
  if (margin_ >= 0.0) {
    const glm::dvec3 n = normal_matrix_ * glm::dvec3(bounds_.normals[k]);
    const double nl = glm::length(n);
    const glm::dvec3 d = view_.eye - c;
    const double dist = glm::length(d);
    if (nl > 0.0 && dist > r) {
      // The directions from the sphere to the eye lie within asin(r / dist) of d: left out when even the nearest of
      // them is more than 90° + margin away from the root normal.
      const double theta = std::acos(std::clamp(glm::dot(n, d) / (nl * dist), -1.0, 1.0));
      const double beta = std::asin(std::min(1.0, r / dist));
      if (theta - beta > 0.5 * M_PI + margin_) return DdmCullReason::facing_away;
    }
  }
  if (view_.keep < 1.0 && ddm_lod_rank(k) >= view_.keep) return DdmCullReason::thinned;
  return DdmCullReason::kept;
}

int DdmCuller::level(std::size_t k) const {
  if (!(view_.pixels_per_unit > 0.0)) return 0;
  const glm::vec4 s = bounds_.spheres[k];
  const glm::dvec4 clip = view_.view_proj * (view_.model * glm::dvec4(s.x, s.y, s.z, 1.0));
  const double r = s.w * scale_;
  if (!(clip.w > 0.0)) return 0;  // reaching behind the eye: full detail
  const double px = 2.0 * r * view_.pixels_per_unit / clip.w;
  int l = 0;
  while (l < 2 && px < kDdmLodPixels[l]) ++l;
  return l;
}

}  // namespace trispline::gpu
