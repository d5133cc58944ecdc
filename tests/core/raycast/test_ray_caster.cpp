// RayCaster against analytic answers: a triangle, a finely tessellated sphere, misses, batches, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/mesh/uv_sphere.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {
namespace {

TriMesh triangle_at_z(double z) {
  TriMesh m;
  m.positions = {{-1, -1, z}, {1, -1, z}, {0, 1, z}};
  m.triangles = {{0, 1, 2}};
  return m;
}

// The UV sphere of radius 1 (core::make_uv_sphere) with `slices` longitude and `stacks` latitude bands, at centre c.
TriMesh sphere(const glm::dvec3& c, int slices, int stacks) {
  TriMesh m = make_uv_sphere(1.0, stacks, slices);
  for (glm::dvec3& p : m.positions) p += c;
  return m;
}

TEST(RayCaster, HitsTriangleAtAnalyticDistance) {
  RayCaster rc;
  EXPECT_EQ(rc.add_mesh(triangle_at_z(2.5)), 0);
  rc.commit();
  const auto hit = rc.intersect({0.1, -0.2, 0}, {0, 0, 7});  // direction need not be unit
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 2.5, 1e-12);
  EXPECT_NEAR(glm::length(hit->position - glm::dvec3(0.1, -0.2, 2.5)), 0, 1e-12);
  EXPECT_EQ(hit->geometry, 0);
  EXPECT_EQ(hit->triangle, 0);
  EXPECT_NEAR(glm::length(hit->normal - glm::dvec3(0, 0, -1)), 0, 1e-12);  // faces the origin

  const auto back = rc.intersect({0.1, -0.2, 5}, {0, 0, -1});  // from the other side: normal flips
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->t, 2.5, 1e-12);
  EXPECT_NEAR(glm::length(back->normal - glm::dvec3(0, 0, 1)), 0, 1e-12);
}

TEST(RayCaster, MissesAndRange) {
  RayCaster rc;
  rc.add_mesh(triangle_at_z(2.5));
  rc.commit();
  EXPECT_FALSE(rc.intersect({5, 5, 0}, {0, 0, 1}));        // beside it
  EXPECT_FALSE(rc.intersect({0, 0, 0}, {0, 0, -1}));       // behind the origin
  EXPECT_FALSE(rc.intersect({0, 0, 0}, {0, 0, 1}, 0, 2));  // t_max before it
  EXPECT_FALSE(rc.intersect({0, 0, 0}, {0, 0, 1}, 3));     // t_min after it
  EXPECT_FALSE(rc.intersect({0, 0, 0}, {0, 0, 0}));        // no direction
}

TEST(RayCaster, SphereDistanceAndNearestOfSeveralMeshes) {
  RayCaster rc;
  rc.add_mesh(TriMesh{});  // accepted, never hit
  const int far_id = rc.add_mesh(sphere({0, 0, 10}, 256, 128));
  const int near_id = rc.add_mesh(sphere({0, 0, 5}, 256, 128));
  rc.commit();
  EXPECT_FALSE(rc.empty());
  const auto hit = rc.intersect({0, 0, 0}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->geometry, near_id);
  EXPECT_NEAR(hit->t, 4.0, 1e-3);  // tessellation error of a 256 × 128 sphere
  // Off-axis ray: distance to a unit sphere at (0,0,5) is 5·cos α − sqrt(1 − 25 sin² α).
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.1, 0.05, 1));
  const auto h2 = rc.intersect({0, 0, 0}, d);
  ASSERT_TRUE(h2);
  const double ca = d.z, sa2 = 1 - ca * ca;
  EXPECT_NEAR(h2->t, 5 * ca - std::sqrt(1 - 25 * sa2), 2e-3);
  EXPECT_NEAR(glm::length(h2->position - glm::dvec3(0, 0, 5)), 1.0, 2e-3);
  EXPECT_LT(glm::dot(h2->normal, d), 0.0);
  const auto h3 = rc.intersect({0, 0, 7.5}, {0, 0, 1});
  ASSERT_TRUE(h3);
  EXPECT_EQ(h3->geometry, far_id);
  EXPECT_NEAR(h3->t, 1.5, 1e-3);
}

TEST(RayCaster, BatchedEqualsSingleAndIsDeterministic) {
  const TriMesh s = sphere({0, 0, 0}, 64, 32);
  std::vector<glm::dvec3> origins, dirs;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      origins.push_back({-1.3 + 2.6 * i / 39, -1.3 + 2.6 * j / 39, -5});
      dirs.push_back({0.01 * i, -0.003 * j, 1});
    }
  RayCaster a;
  a.add_mesh(s);
  a.commit();
  const auto batch = a.intersect_all(origins, dirs);
  ASSERT_EQ(batch.size(), origins.size());
  int hits = 0;
  for (std::size_t r = 0; r < origins.size(); ++r) {
    const auto single = a.intersect(origins[r], dirs[r]);
    ASSERT_EQ(single.has_value(), batch[r].has_value()) << r;
    if (!single) continue;
    ++hits;
    EXPECT_EQ(single->t, batch[r]->t);
    EXPECT_EQ(single->triangle, batch[r]->triangle);
    EXPECT_EQ(single->position, batch[r]->position);
  }
  EXPECT_GT(hits, 300);
  EXPECT_LT(hits, int(origins.size()));

  RayCaster b;  // a second build of the same scene gives bit-identical hits
  b.add_mesh(s);
  b.commit();
  const auto again = b.intersect_all(origins, dirs);
  for (std::size_t r = 0; r < origins.size(); ++r) {
    ASSERT_EQ(again[r].has_value(), batch[r].has_value());
    if (again[r]) {
      EXPECT_EQ(again[r]->t, batch[r]->t);
      EXPECT_EQ(again[r]->triangle, batch[r]->triangle);
      EXPECT_EQ(again[r]->normal, batch[r]->normal);
    }
  }
  RayCaster moved = std::move(b);  // movable
  EXPECT_TRUE(moved.intersect(origins[820], dirs[820]).has_value() == batch[820].has_value());
}

TEST(RayCaster, Errors) {
  RayCaster rc;
  TriMesh bad = triangle_at_z(1);
  bad.positions[1].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(rc.add_mesh(bad), std::invalid_argument);
  EXPECT_THROW(rc.intersect({0, 0, 0}, {0, 0, 1}), std::logic_error);  // before commit
  EXPECT_THROW(rc.intersect_all({{0, 0, 0}}, {}), std::invalid_argument);
  rc.commit();
  EXPECT_TRUE(rc.empty());
  EXPECT_FALSE(rc.intersect({0, 0, 0}, {0, 0, 1}));
}

}  // namespace
}  // namespace trispline::core
