// Chart sizes for laying tiles by world size. See ddm_chart_size.h.
#include "core/ddm/ddm_chart_size.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace trispline::core {

glm::dvec2 ddm_chart_size(const DdmBase& base, int chart, int samples) {
  glm::dvec2 sum(0.0);
  for (int j = 0; j < samples; ++j)
    for (int i = 0; i < samples; ++i) {
      const DdmSurfacePoint s = base.eval(chart, (i + 0.5) / samples, (j + 0.5) / samples);
      sum += glm::dvec2(glm::length(s.du), glm::length(s.dv));
    }
  return sum / double(samples * samples);
}

std::vector<glm::dvec2> ddm_limit_chart_sizes(const TriMesh& mesh) {
  std::vector<glm::dvec2> sizes;
  sizes.reserve(3 * mesh.triangle_count());
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      if (t[k] >= mesh.vertex_count()) throw std::invalid_argument("base: a triangle index ≥ #V");
    for (int k = 0; k < 3; ++k) {
      // DdmSubdivBase's chart 3f + k: A = vertex k, B = middle of edge (k, k+1), C = centre, D = middle of (k+2, k).
      const glm::dvec3 a = mesh.positions[t[k]], b = mesh.positions[t[(k + 1) % 3]], c = mesh.positions[t[(k + 2) % 3]];
      const glm::dvec3 A = a, B = 0.5 * (a + b), C = (a + b + c) / 3.0, D = 0.5 * (a + c);
      sizes.push_back(
          {0.5 * (glm::length(B - A) + glm::length(C - D)), 0.5 * (glm::length(D - A) + glm::length(C - B))});
    }
  }
  return sizes;
}

glm::dvec2 ddm_uv_chart_size(const TriMesh& mesh) {
  if (mesh.uvs.size() != mesh.vertex_count())
    throw std::invalid_argument("base: the mesh has no texture coordinates (" + std::to_string(mesh.uvs.size()) +
                                " uvs for " + std::to_string(mesh.vertex_count()) + " vertices)");
  double world = 0.0, uv = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    if (t[0] >= mesh.vertex_count() || t[1] >= mesh.vertex_count() || t[2] >= mesh.vertex_count())
      throw std::invalid_argument("base: a triangle index ≥ #V");
    world += 0.5 * glm::length(glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                          mesh.positions[t[2]] - mesh.positions[t[0]]));
    const glm::dvec2 e1 = mesh.uvs[t[1]] - mesh.uvs[t[0]], e2 = mesh.uvs[t[2]] - mesh.uvs[t[0]];
    uv += 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
  }
  if (!(uv > 0.0) || !std::isfinite(world / uv))
    throw std::invalid_argument("base: the texture coordinates have no area");
  const double s = std::sqrt(world / uv);
  return {s, s};
}

}  // namespace trispline::core
