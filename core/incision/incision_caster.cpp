// stroke_ray_caster(): a RayCaster over the triangles a stroke's rays can hit (incision.draw's ray casting).
#include <algorithm>
#include <cmath>

#include "core/incision/incision.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/camera.h"

namespace trispline::core {

RayCaster stroke_ray_caster(const TriMesh& surface, const Camera& camera, const std::vector<glm::dvec2>& stroke_px,
                            BuildQuality quality) {
  // Projection as Camera::project, with the basis computed once.
  const glm::dvec3 fw = camera.forward(), rt = camera.right(), up = camera.true_up();
  const double tan_half = std::tan(glm::radians(camera.fov_deg) * 0.5);
  const double sx = 0.5 * camera.viewport.x / (tan_half * camera.aspect()), sy = 0.5 * camera.viewport.y / tan_half;
  const std::size_t V = surface.positions.size();
  std::vector<glm::dvec2> px(V);
  std::vector<std::uint8_t> behind(V, 0);
  for (std::size_t v = 0; v < V; ++v) {
    const glm::dvec3 rel = surface.positions[v] - camera.eye;
    const double depth = glm::dot(rel, fw);
    if (!(depth > 1e-12)) {
      behind[v] = 1;
      continue;
    }
    px[v] = {0.5 * camera.viewport.x + sx * glm::dot(rel, rt) / depth,
             0.5 * camera.viewport.y - sy * glm::dot(rel, up) / depth};
  }
  // Stroke pixels in chunks of 8 with their bounding boxes.
  struct Chunk {
    glm::dvec2 lo{1e300}, hi{-1e300};
    std::size_t begin = 0, end = 0;
  };
  std::vector<glm::dvec2> pts;
  for (const glm::dvec2& p : stroke_px)
    if (std::isfinite(p.x) && std::isfinite(p.y)) pts.push_back(p);
  std::vector<Chunk> chunks;
  for (std::size_t b = 0; b < pts.size(); b += 8) {
    Chunk c;
    c.begin = b, c.end = std::min(pts.size(), b + 8);
    for (std::size_t i = c.begin; i < c.end; ++i) c.lo = glm::min(c.lo, pts[i]), c.hi = glm::max(c.hi, pts[i]);
    chunks.push_back(c);
  }
  const double margin = 2.0;  // pixels: float rounding in the ray tracer, pixel-centre conventions
  // The kept triangles over only the vertices they use (hits give positions and normals, never input indices).
  TriMesh sub;
  std::vector<std::uint32_t> remap;
  auto use = [&](std::uint32_t v) {
    if (remap.empty()) remap.assign(V, ~0u);
    if (remap[v] == ~0u) {
      remap[v] = static_cast<std::uint32_t>(sub.positions.size());
      sub.positions.push_back(surface.positions[v]);
    }
    return remap[v];
  };
  for (const glm::uvec3& t : surface.triangles) {
    bool keep = behind[t.x] || behind[t.y] || behind[t.z];
    if (!keep) {
      const glm::dvec2 lo = glm::min(glm::min(px[t.x], px[t.y]), px[t.z]) - margin;
      const glm::dvec2 hi = glm::max(glm::max(px[t.x], px[t.y]), px[t.z]) + margin;
      for (const Chunk& c : chunks) {
        if (c.hi.x < lo.x || c.lo.x > hi.x || c.hi.y < lo.y || c.lo.y > hi.y) continue;
        for (std::size_t i = c.begin; i < c.end && !keep; ++i)
          keep = pts[i].x >= lo.x && pts[i].x <= hi.x && pts[i].y >= lo.y && pts[i].y <= hi.y;
        if (keep) break;
      }
    }
    if (keep) sub.triangles.emplace_back(use(t.x), use(t.y), use(t.z));
  }
  RayCaster rc(quality);
  rc.add_mesh(sub);
  rc.commit();
  return rc;
}

}  // namespace trispline::core
