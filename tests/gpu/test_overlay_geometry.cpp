#include <gtest/gtest.h>

#include "gpu/overlay_geometry.h"

namespace trispline::gpu {

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

}  // namespace trispline::gpu
