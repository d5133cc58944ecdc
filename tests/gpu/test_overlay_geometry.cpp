#include <gtest/gtest.h>

#include <cmath>

#include "gpu/view/overlay_geometry.h"

namespace trispline::gpu {
namespace {

// A bent, twisted lattice with different orders and counts per axis (clamped knots, domain [0,1]³).
core::TrivariateBSpline<glm::dvec3> bent_lattice() {
  using core::KnotVector;
  const glm::ivec3 n(7, 4, 3);
  std::vector<glm::dvec3> cps;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const double x = -1.5 + 3.0 * i / (n.x - 1), z = -0.6 + 1.2 * j / (n.y - 1);
        cps.push_back({x + 0.05 * std::sin(3.0 * j + i), 0.3 * std::sin(1.3 * x) + 0.1 * z * x + 0.4 * k,
                       z + 0.07 * std::cos(2.0 * i - k)});
      }
  return {KnotVector::clamped_uniform(4, n.x), KnotVector::clamped_uniform(3, n.y), KnotVector::clamped_uniform(2, n.z),
          cps};
}

}  // namespace

TEST(OverlayGeometry, ThickPolylineCoversTheStroke) {
  const std::vector<glm::vec2> tris = thick_polyline({{10.0, 10.0}, {50.0, 10.0}}, 4.0f, 8);
  ASSERT_EQ(tris.size() % 3, 0u);
  EXPECT_EQ(tris.size(), 2u * 8u * 3u + 6u);  // two discs + one quad
  for (const glm::vec2& p : tris) {
    EXPECT_GE(p.x, 8.0f - 1e-4f);
    EXPECT_LE(p.x, 52.0f + 1e-4f);
    EXPECT_NEAR(p.y, 10.0f, 2.0f + 1e-4f);
  }
  EXPECT_TRUE(thick_polyline({}, 4.0f).empty());
  EXPECT_EQ(thick_polyline({{1.0, 1.0}}, 4.0f, 6).size(), 18u);  // a single point is a disc
}

TEST(OverlayGeometry, ContactSurfaceColoursHitsAndFills) {
  core::PlacementRecord r;
  r.samples_u = 3;
  r.samples_v = 2;
  for (int i = 0; i < 6; ++i) r.contact_points.push_back({double(i % 3), 0.0, double(i / 3)});
  r.contact_hit = {1, 1, 0, 1, 1, 1};
  std::vector<OverlayVertex> lines, points;
  const glm::vec4 hit(0, 1, 0, 1), filled(1, 0, 0, 1), grid(1, 1, 1, 1);
  append_contact_surface(r, hit, filled, grid, lines, points);
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[2].color, filled);
  EXPECT_EQ(points[0].color, hit);
  EXPECT_EQ(lines.size(), 2u * (2 * 2 + 3 * 1));  // (nu-1)·nv + nu·(nv-1) segments
}

TEST(OverlayGeometry, ContactSurfaceTessellationLiesOnFOfUV0) {
  const core::TrivariateBSpline<glm::dvec3> F = bent_lattice();
  const ContactSurfaceTessellation t = tessellate_contact_surface(F, 48, 16);
  ASSERT_EQ(t.vertices_u, 49);
  ASSERT_EQ(t.vertices_v, 17);
  const core::TriMesh& m = t.mesh;
  ASSERT_EQ(m.positions.size(), 49u * 17u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  EXPECT_EQ(m.triangles.size(), 2u * 48u * 16u);
  for (const glm::uvec3& f : m.triangles) EXPECT_LT(std::max({f.x, f.y, f.z}), m.positions.size());

  // Clamped knots interpolate the corner control points of layer k = 0.
  const glm::ivec3 n = F.control_counts();
  auto expect_at = [](const glm::dvec3& got, const glm::dvec3& want, const char* what) {
    EXPECT_NEAR(got.x, want.x, 1e-12) << what;
    EXPECT_NEAR(got.y, want.y, 1e-12) << what;
    EXPECT_NEAR(got.z, want.z, 1e-12) << what;
  };
  expect_at(m.positions[t.index(0, 0)], F.control_point(0, 0, 0), "S(0,0)");
  expect_at(m.positions[t.index(48, 0)], F.control_point(n.x - 1, 0, 0), "S(1,0)");
  expect_at(m.positions[t.index(0, 16)], F.control_point(0, n.y - 1, 0), "S(0,1)");
  expect_at(m.positions[t.index(48, 16)], F.control_point(n.x - 1, n.y - 1, 0), "S(1,1)");

  // Every vertex is F(u, v, 0) at its own (u, v); the (u, v) are a uniform grid over [0,1]², u fastest.
  for (int b = 0; b <= 16; ++b)
    for (int a = 0; a <= 48; ++a) {
      const std::size_t i = t.index(a, b);
      EXPECT_NEAR(m.uvs[i].x, a / 48.0, 1e-15);
      EXPECT_NEAR(m.uvs[i].y, b / 16.0, 1e-15);
      expect_at(m.positions[i], F.eval({m.uvs[i].x, m.uvs[i].y, 0.0}), "vertex");
      EXPECT_NEAR(glm::length(m.normals[i]), 1.0, 1e-12);
      const auto d = F.eval_first({m.uvs[i].x, m.uvs[i].y, 0.0}).d;
      EXPECT_NEAR(glm::dot(m.normals[i], d[0]), 0.0, 1e-9);  // normal ⟂ ∂S/∂u and ∂S/∂v
      EXPECT_NEAR(glm::dot(m.normals[i], d[1]), 0.0, 1e-9);
    }
  // Triangles wind counter-clockwise about the normal.
  const glm::uvec3 f = m.triangles[0];
  EXPECT_GT(
      glm::dot(glm::cross(m.positions[f.y] - m.positions[f.x], m.positions[f.z] - m.positions[f.x]), m.normals[f.x]),
      0.0);
  EXPECT_THROW(tessellate_contact_surface(F, 0, 4), std::invalid_argument);
}

TEST(OverlayGeometry, ContactIsoLinesEveryFewGridLinesAndTheBoundary) {
  const ContactSurfaceTessellation t = tessellate_contact_surface(bent_lattice(), 8, 5);
  std::vector<OverlayVertex> lines;
  const glm::vec4 c(1, 1, 1, 0.5f);
  append_contact_iso_lines(t, 4, 4, c, lines);
  // Constant u: a = 0, 4, 8 (3 lines × 5 segments); constant v: b = 0, 4, 5 (3 lines × 8 segments).
  ASSERT_EQ(lines.size(), 2u * (3 * 5 + 3 * 8));
  for (const OverlayVertex& v : lines) EXPECT_EQ(v.color, c);
  EXPECT_EQ(lines[0].position, glm::vec3(t.mesh.positions[t.index(0, 0)]));
  EXPECT_EQ(lines[1].position, glm::vec3(t.mesh.positions[t.index(0, 1)]));
  lines.clear();
  append_contact_iso_lines(t, 1, 1, c, lines);
  EXPECT_EQ(lines.size(), 2u * (9 * 5 + 6 * 8));  // every grid edge
}

}  // namespace trispline::gpu

namespace trispline::gpu {

// F⁻ / F⁺ of a discontinuity along v: one m-plane each, its points in its colour, its polylines along u and w.
TEST(OverlayGeometry, DiscontinuityPlanesListTheirControlPoints) {
  core::TrivariateBSpline<glm::dvec3> F = bent_lattice();  // 7 × 4 × 3 controls, orders (4, 3, 2)
  const core::Discontinuity d = core::insert_discontinuity(F, 1, 0.5);
  const glm::ivec3 n = F.control_counts();
  ASSERT_EQ(d.plus_plane, d.minus_plane + 1);
  const glm::vec4 red{1, 0, 0, 1}, cyan{0, 1, 1, 1};
  std::vector<OverlayVertex> lines, minus, plus;
  append_discontinuity_planes(F, {d}, red, cyan, lines, minus, plus);
  ASSERT_EQ(minus.size(), std::size_t(n.x * n.z));
  ASSERT_EQ(plus.size(), std::size_t(n.x * n.z));
  std::size_t q = 0;
  for (int k = 0; k < n.z; ++k)
    for (int i = 0; i < n.x; ++i, ++q) {
      EXPECT_EQ(minus[q].position, glm::vec3(F.control_point(i, d.minus_plane, k)));
      EXPECT_EQ(plus[q].position, glm::vec3(F.control_point(i, d.plus_plane, k)));
      EXPECT_EQ(minus[q].color, red);
      EXPECT_EQ(plus[q].color, cyan);
    }
  // Per plane: (l−1)·n + l·(n−1) segments, two vertices each.
  EXPECT_EQ(lines.size(), 2u * 2u * std::size_t((n.x - 1) * n.z + n.x * (n.z - 1)));
  // Out-of-range planes and axes are left out.
  core::Discontinuity bad = d;
  bad.axis = 3;
  core::Discontinuity far = d;
  far.minus_plane = n.y;
  far.plus_plane = n.y + 1;
  lines.clear();
  minus.clear();
  plus.clear();
  append_discontinuity_planes(F, {bad, far}, red, cyan, lines, minus, plus);
  EXPECT_TRUE(lines.empty() && minus.empty() && plus.empty());
}

TEST(OverlayGeometry, SphereTrianglesLieOnTheSphereAndFaceOutwards) {
  SphereOverlay sphere;
  sphere.centre = {1.0, 2.0, -0.5};
  sphere.radius = 0.25;
  std::vector<OverlayVertex> tris;
  append_sphere(sphere, {0.0f, 0.0f, 5.0f}, tris, 16, 8);
  ASSERT_EQ(tris.size(), std::size_t(6 * 16 * (8 - 1)));
  const glm::vec3 c(sphere.centre);
  for (std::size_t i = 0; i < tris.size(); i += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(glm::length(tris[i + k].position - c), 0.25f, 1e-5f);
      EXPECT_GT(tris[i + k].color.w, 0.0f);
      EXPECT_LE(tris[i + k].color.w, 1.0f);
    }
    const glm::vec3 n = glm::cross(tris[i + 1].position - tris[i].position, tris[i + 2].position - tris[i].position);
    const glm::vec3 mid = (tris[i].position + tris[i + 1].position + tris[i + 2].position) / 3.0f;
    EXPECT_GT(glm::dot(n, mid - c), 0.0f) << "triangle " << i / 3 << " must be CCW seen from outside";
  }
}

}  // namespace trispline::gpu
