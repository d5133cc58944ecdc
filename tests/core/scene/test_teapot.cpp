// The Utah teapot from Newell's 32 Bézier patches through BSplineSurface.
#include "core/scene/primitives.h"
#include "core/spline/bspline_surface.h"
#include "primitive_checks.h"

namespace trispline::core {
namespace {

TEST(Teapot, StandsOnGroundWithHeightOne) {
  const TriMesh m = make_primitive(PrimitiveKind::Teapot);
  test::expect_valid_with_unit_normals(m, "teapot");
  const Aabb b = mesh_bounds(m);
  EXPECT_NEAR(b.lo.y, 0.0, 1e-15);
  EXPECT_NEAR(b.hi.y, 1.0, 1e-12);
  EXPECT_NEAR(b.center().z, 0.0, 1e-12);  // symmetric about the xy-plane
  // The body's axis of revolution is the y axis: the body's widest ring (y ≈ 0.4) is centred on it.
  double xmin = 1e9, xmax = -1e9;
  for (const auto& p : m.positions)
    if (std::abs(p.y - 0.4) < 0.02 && std::abs(p.z) < 0.05 && std::abs(p.x) < 0.7) {
      xmin = std::min(xmin, p.x);
      xmax = std::max(xmax, p.x);
    }
  EXPECT_NEAR(xmin + xmax, 0.0, 0.02);
  // Newell's proportions: 3.15 tall; spout tip to handle ~6.4 across (x), body 4 deep (z) → / 3.15.
  EXPECT_NEAR(b.size().z, 4.0 / 3.15, 0.02);
  EXPECT_GT(b.size().x, 1.9);
  EXPECT_LT(b.size().x, 2.1);
  // Spout towards +x: the highest point right of the centre plane is the spout tip, well above the body's middle.
  double spout_y = 0;
  for (const auto& p : m.positions)
    if (p.x > 0.8) spout_y = std::max(spout_y, p.y);
  EXPECT_GT(spout_y, 0.6);
}

TEST(Teapot, ThirtyTwoPatchesWorthOfTriangles) {
  for (int s : {4, 10}) {
    const TriMesh m = make_teapot(s);
    // 32 patches × 2s² triangles, less the s triangles each of the 4 lid and 4 bottom patches loses at its pole.
    EXPECT_EQ(m.triangle_count(), std::size_t(32 * 2 * s * s - 8 * s)) << s;
    EXPECT_LT(m.vertex_count(), std::size_t(32 * (s + 1) * (s + 1))) << "patch borders are welded";
  }
  EXPECT_EQ(make_primitive(PrimitiveKind::Teapot).triangle_count(), std::size_t(32 * 200 - 80));
}

TEST(Teapot, OrientedOutwardsAndWelded) {
  const TriMesh m = make_teapot(10);
  EXPECT_GT(signed_volume(m), 0.0);  // CCW seen from outside
  // No edge is used twice in one direction: all patches agree on orientation across welded borders.
  int boundary = 0;
  EXPECT_EQ(test::orientation_defects(m, &boundary), 0);
  // Open borders remain only where Newell's model is open: lid/body gap, spout and handle ends against the body.
  EXPECT_GT(boundary, 0);
  EXPECT_LT(boundary, 8 * 10 * 4);
  // Vertex normals agree with the faces around them (outwards).
  std::vector<glm::dvec3> face_sum(m.vertex_count(), glm::dvec3(0));
  for (const auto& t : m.triangles) {
    const glm::dvec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    for (int k = 0; k < 3; ++k) face_sum[t[k]] += n;
  }
  int disagree = 0;
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    if (glm::dot(face_sum[i], m.normals[i]) <= 0) ++disagree;
  EXPECT_EQ(disagree, 0);
  // The lid knob's pole has a vertical normal.
  std::size_t top = 0;
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    if (m.positions[i].y > m.positions[top].y) top = i;
  EXPECT_NEAR(m.normals[top].y, 1.0, 1e-6);
}

TEST(Teapot, VerticesLieOnTheBezierPatchesOfTheData) {
  const TriMesh m = make_teapot(10);
  const double s = 1.0 / 3.15;  // Newell's teapot is 3.15 tall
  // The lid knob's pole, Newell's (0, 0, 3.15), is the highest vertex: it gives the body axis (x = y = 0 there).
  glm::dvec3 axis = m.positions[0];
  for (const auto& p : m.positions)
    if (p.y > axis.y) axis = p;
  EXPECT_NEAR(axis.y, 1.0, 1e-12);
  const KnotVector bezier(4, {0, 0, 0, 0, 1, 1, 1, 1});
  for (int patch : {0, 5, 13, 17, 22, 30}) {
    std::vector<glm::dvec3> cps;
    for (int k = 0; k < 16; ++k) {
      const double* q = detail::kTeapotVertices[detail::kTeapotPatches[patch][k]];
      cps.push_back({q[0], q[2], -q[1]});
    }
    const BSplineSurface<glm::dvec3> surf(bezier, bezier, cps);
    const glm::dvec3 expected = surf.eval(0.3, 0.7) * s + glm::dvec3(axis.x, 0, axis.z);
    double best = 1e300;
    for (const auto& p : m.positions) best = std::min(best, glm::length(p - expected));
    EXPECT_LT(best, 1e-9) << "patch " << patch;
  }
  EXPECT_EQ(detail::kTeapotPatchCount, 32);
}

}  // namespace
}  // namespace trispline::core
