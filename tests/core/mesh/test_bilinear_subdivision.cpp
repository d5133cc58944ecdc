// Uniform bilinear refinement (core/mesh/bilinear_subdivision.h): counts, planarity, winding.
#include <gtest/gtest.h>

#include "core/mesh/bilinear_subdivision.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/uv_sphere.h"

using namespace trispline::core;

TEST(Subdivision, BilinearLevelOneCountsAndPlanarity) {
  TriMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};
  const TriMesh s = subdivide_bilinear(quad, 1);
  EXPECT_EQ(s.positions.size(), 4u + 5u + 2u);  // V + E + F
  EXPECT_EQ(s.triangles.size(), 2u * 3u * 2u);  // each triangle → 3 quads → 6 triangles
  for (const auto& p : s.positions) EXPECT_DOUBLE_EQ(p.y, 0.0);
  EXPECT_EQ(subdivide_bilinear(quad, 0).positions.size(), 4u);
  TriMesh sphere = make_uv_sphere(1.0, 8, 16);
  EXPECT_GT(signed_volume(subdivide_bilinear(sphere, 2)), 0.0);  // winding kept
}
