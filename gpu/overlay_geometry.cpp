#include "gpu/overlay_geometry.h"

#include <cmath>

namespace trispline::gpu {

void append_lattice(const core::TrivariateBSpline<glm::dvec3>& lattice, const glm::vec4& line_color,
                    const glm::vec4& point_color, std::vector<OverlayVertex>& lines,
                    std::vector<OverlayVertex>& points) {
  const glm::ivec3 n = lattice.control_counts();
  auto cp = [&](int i, int j, int k) { return glm::vec3(lattice.control_point(i, j, k)); };
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::vec3 p = cp(i, j, k);
        points.push_back({p, point_color});
        if (i + 1 < n.x) lines.insert(lines.end(), {{p, line_color}, {cp(i + 1, j, k), line_color}});
        if (j + 1 < n.y) lines.insert(lines.end(), {{p, line_color}, {cp(i, j + 1, k), line_color}});
        if (k + 1 < n.z) lines.insert(lines.end(), {{p, line_color}, {cp(i, j, k + 1), line_color}});
      }
}

void append_contact_surface(const core::PlacementRecord& placement, const glm::vec4& hit_color,
                            const glm::vec4& filled_color, const glm::vec4& grid_color,
                            std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& points) {
  const std::vector<glm::dvec3>& c = placement.contact_points;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool hit = i < placement.contact_hit.size() ? placement.contact_hit[i] != 0 : true;
    points.push_back({glm::vec3(c[i]), hit ? hit_color : filled_color});
  }
  const int nu = placement.samples_u, nv = placement.samples_v;
  if (nu <= 0 || nv <= 0 || std::size_t(nu) * std::size_t(nv) != c.size()) return;  // no grid to connect
  auto at = [&](int a, int b) { return glm::vec3(c[std::size_t(a) + std::size_t(nu) * std::size_t(b)]); };
  for (int b = 0; b < nv; ++b)
    for (int a = 0; a < nu; ++a) {
      if (a + 1 < nu) lines.insert(lines.end(), {{at(a, b), grid_color}, {at(a + 1, b), grid_color}});
      if (b + 1 < nv) lines.insert(lines.end(), {{at(a, b), grid_color}, {at(a, b + 1), grid_color}});
    }
}

std::vector<glm::vec2> thick_polyline(const std::vector<glm::dvec2>& px, float width_px, int segments) {
  std::vector<glm::vec2> tris;
  if (px.empty() || width_px <= 0.0f) return tris;
  const float r = 0.5f * width_px;
  segments = segments < 3 ? 3 : segments;
  auto disc = [&](glm::vec2 c) {
    for (int s = 0; s < segments; ++s) {
      const float a0 = 6.2831853f * float(s) / float(segments), a1 = 6.2831853f * float(s + 1) / float(segments);
      tris.insert(tris.end(),
                  {c, c + r * glm::vec2(std::cos(a0), std::sin(a0)), c + r * glm::vec2(std::cos(a1), std::sin(a1))});
    }
  };
  for (std::size_t i = 0; i < px.size(); ++i) {
    const glm::vec2 a(px[i]);
    disc(a);  // round join / cap
    if (i + 1 == px.size()) break;
    const glm::vec2 b(px[i + 1]);
    const glm::vec2 d = b - a;
    const float len = glm::length(d);
    if (len <= 0.0f) continue;
    const glm::vec2 n = glm::vec2(-d.y, d.x) / len * r;
    tris.insert(tris.end(), {a + n, a - n, b + n, b + n, a - n, b - n});
  }
  return tris;
}

}  // namespace trispline::gpu
