#include "gpu/view/overlay_geometry.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <stdexcept>

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

void append_discontinuity_planes(const core::TrivariateBSpline<glm::dvec3>& lattice,
                                 const std::vector<core::Discontinuity>& discs, const glm::vec4& minus_color,
                                 const glm::vec4& plus_color, std::vector<OverlayVertex>& lines,
                                 std::vector<OverlayVertex>& minus_points, std::vector<OverlayVertex>& plus_points) {
  const glm::ivec3 n = lattice.control_counts();
  for (const core::Discontinuity& d : discs) {
    if (d.axis < 0 || d.axis > 2) continue;
    const int a = d.axis, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;  // the other two axes, b fastest
    for (const int plane : {d.minus_plane, d.plus_plane}) {
      if (plane < 0 || plane >= n[a]) continue;
      const bool minus = plane == d.minus_plane;
      const glm::vec4& color = minus ? minus_color : plus_color;
      std::vector<OverlayVertex>& points = minus ? minus_points : plus_points;
      auto cp = [&](int ib, int ic) {
        glm::ivec3 idx;
        idx[a] = plane;
        idx[b] = ib;
        idx[c] = ic;
        return glm::vec3(lattice.control_point(idx.x, idx.y, idx.z));
      };
      for (int ic = 0; ic < n[c]; ++ic)
        for (int ib = 0; ib < n[b]; ++ib) {
          const glm::vec3 p = cp(ib, ic);
          points.push_back({p, color});
          if (ib + 1 < n[b]) lines.insert(lines.end(), {{p, color}, {cp(ib + 1, ic), color}});
          if (ic + 1 < n[c]) lines.insert(lines.end(), {{p, color}, {cp(ib, ic + 1), color}});
        }
    }
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

ContactSurfaceTessellation tessellate_contact_surface(const core::TrivariateBSpline<glm::dvec3>& lattice, int cells_u,
                                                      int cells_v) {
  if (cells_u < 1 || cells_v < 1) throw std::invalid_argument("tessellate_contact_surface: cell counts must be >= 1");
  ContactSurfaceTessellation t;
  t.vertices_u = cells_u + 1;
  t.vertices_v = cells_v + 1;
  const core::KnotVector &ku = lattice.knots(0), &kv = lattice.knots(1);
  const double w0 = lattice.knots(2).domain_min();
  // Exact ends: the last parameter is domain_max itself, not an accumulated sum.
  auto param = [](const core::KnotVector& k, int i, int cells) {
    if (i == cells) return k.domain_max();
    return k.domain_min() + (k.domain_max() - k.domain_min()) * double(i) / double(cells);
  };
  const std::size_t n = std::size_t(t.vertices_u) * std::size_t(t.vertices_v);
  core::TriMesh& m = t.mesh;
  m.positions.resize(n);
  m.normals.resize(n);
  m.uvs.resize(n);
  for (int b = 0; b < t.vertices_v; ++b)
    for (int a = 0; a < t.vertices_u; ++a) {
      const std::size_t i = t.index(a, b);
      const glm::dvec2 uv(param(ku, a, cells_u), param(kv, b, cells_v));
      const auto f = lattice.eval_first({uv.x, uv.y, w0});
      const glm::dvec3 nrm = glm::cross(f.d[0], f.d[1]);
      const double len = glm::length(nrm);
      m.uvs[i] = uv;
      m.positions[i] = lattice.eval({uv.x, uv.y, w0});  // the plain evaluator: bit-identical to F itself
      m.normals[i] = len > 1e-300 && std::isfinite(len) ? nrm / len : glm::dvec3(0.0, 1.0, 0.0);
    }
  m.triangles.reserve(2 * std::size_t(cells_u) * std::size_t(cells_v));
  for (int b = 0; b < cells_v; ++b)
    for (int a = 0; a < cells_u; ++a) {
      const auto i00 = unsigned(t.index(a, b)), i10 = unsigned(t.index(a + 1, b));
      const auto i01 = unsigned(t.index(a, b + 1)), i11 = unsigned(t.index(a + 1, b + 1));
      m.triangles.push_back({i00, i10, i11});  // CCW about ∂S/∂u × ∂S/∂v
      m.triangles.push_back({i00, i11, i01});
    }
  return t;
}

void append_contact_iso_lines(const ContactSurfaceTessellation& t, int every_u, int every_v, const glm::vec4& color,
                              std::vector<OverlayVertex>& lines) {
  const int nu = t.vertices_u, nv = t.vertices_v;
  if (nu < 2 || nv < 2 || t.mesh.positions.size() != std::size_t(nu) * std::size_t(nv)) return;
  every_u = std::max(every_u, 1);
  every_v = std::max(every_v, 1);
  auto at = [&](int a, int b) { return glm::vec3(t.mesh.positions[t.index(a, b)]); };
  auto keep = [](int i, int n, int every) { return i % every == 0 || i == n - 1; };
  for (int a = 0; a < nu; ++a)  // lines of constant u, running along v
    if (keep(a, nu, every_u))
      for (int b = 0; b + 1 < nv; ++b) lines.insert(lines.end(), {{at(a, b), color}, {at(a, b + 1), color}});
  for (int b = 0; b < nv; ++b)  // lines of constant v, running along u
    if (keep(b, nv, every_v))
      for (int a = 0; a + 1 < nu; ++a) lines.insert(lines.end(), {{at(a, b), color}, {at(a + 1, b), color}});
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

void append_sphere(const SphereOverlay& s, const glm::vec3& eye, std::vector<OverlayVertex>& out, int slices,
                   int stacks) {
  if (!(s.radius > 0.0) || slices < 3 || stacks < 2) return;
  const glm::vec3 c(s.centre);
  const float r = float(s.radius);
  // Unit normal at (slice a, stack b): b = 0 is the north pole (+y), b = stacks the south pole.
  auto normal = [&](int a, int b) {
    const float theta = glm::pi<float>() * float(b) / float(stacks);
    const float phi = glm::two_pi<float>() * float(a) / float(slices);
    return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  auto vertex = [&](const glm::vec3& n) {
    const glm::vec3 p = c + r * n;
    const glm::vec3 to_eye = glm::normalize(eye - p);
    const float facing = std::abs(glm::dot(n, to_eye));
    const float rim = 1.0f - facing;
    const glm::vec3 rgb = glm::vec3(s.color) * (0.55f + 0.45f * facing) + 0.25f * rim * glm::vec3(1.0f);
    const float alpha = glm::min(1.0f, s.color.w * (1.0f + 1.5f * rim * rim));
    return OverlayVertex{p, glm::vec4(glm::min(rgb, glm::vec3(1.0f)), alpha)};
  };
  for (int b = 0; b < stacks; ++b) {
    for (int a = 0; a < slices; ++a) {
      const glm::vec3 n00 = normal(a, b), n10 = normal(a + 1, b), n01 = normal(a, b + 1), n11 = normal(a + 1, b + 1);
      // Seen from outside, increasing phi runs clockwise around +y: (00, 10, 11) is CCW from outside.
      if (b > 0) out.insert(out.end(), {vertex(n00), vertex(n10), vertex(n11)});
      if (b < stacks - 1) out.insert(out.end(), {vertex(n00), vertex(n11), vertex(n01)});
    }
  }
}

}  // namespace trispline::gpu
