// Sketch placement on generated scenes with analytic surfaces: contact, orientation, volumes, determinism.
#include <gtest/gtest.h>

#include <cstring>

#include "core/mesh/mesh_io.h"
#include "placement_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

struct Scenario {
  const char* name;
  TriMesh scene;
  std::function<double(const glm::dvec3&)> distance;  // unsigned distance to the analytic target surface
  double size;                                        // scene size (bounding-box diagonal)
};

std::vector<Scenario> scenarios() {
  std::vector<Scenario> s;
  s.push_back({"plane", height_field(5.0, 10, [](double, double) { return 0.0; }),
               [](const glm::dvec3& p) { return std::abs(p.y); }, 0});
  const double R = 4.0;
  TriMesh sphere = make_uv_sphere(R, 128, 256);
  for (auto& p : sphere.positions) p.y -= R;
  s.push_back(
      {"sphere", sphere, [R](const glm::dvec3& p) { return std::abs(glm::length(p - glm::dvec3(0, -R, 0)) - R); }, 0});
  const double a = glm::radians(20.0);
  const glm::dvec3 n(0.0, std::cos(a), std::sin(a));  // plane through the origin tilted 20° about x
  TriMesh tilted = height_field(5.0, 10, [a](double, double z) { return -std::tan(a) * z; });
  s.push_back({"tilted", tilted, [n](const glm::dvec3& p) { return std::abs(glm::dot(p, n)); }, 0});
  s.push_back({"terrain", height_field(5.0, 200, bumps),
               [](const glm::dvec3& p) { return std::abs(p.y - bumps(p.x, p.z)); }, 0});
  for (auto& sc : s) {
    Aabb b;
    for (const auto& p : sc.scene.positions) b.extend(p);
    sc.size = b.diagonal();
  }
  return s;
}

TriMesh object_box() { return tessellated_box({2.0, 0.5, 0.6}, {5.0, 5.0, 5.0}, 8); }

TriMesh placed_mesh(const TriMesh& rest, const SketchPlacementResult& r) {
  TriMesh m = rest;
  m.positions = r.positions;
  return m;
}

}  // namespace

TEST(SketchPlacement, BottomLandsOnSurfaceOrientationKept) {
  const TriMesh obj = object_box();
  ASSERT_GT(signed_volume(obj), 0.0);
  for (const auto& sc : scenarios())
    for (const auto& stroke : {straight_stroke(), curved_stroke()})
      for (auto vol : {PlacementVolume::Extrude, PlacementVolume::Offset}) {
        const RayCaster rc = caster_for(sc.scene);
        SketchPlacementParams p = default_params(stroke);
        p.volume = vol;
        const SketchPlacementResult r = place_along_stroke(rc, p, obj.positions);
        const std::string what = std::string(sc.name) + (stroke.size() > 4 ? " curved" : " straight") +
                                 (vol == PlacementVolume::Extrude ? " extrude" : " offset");
        // (b) every ray hits these scenes
        EXPECT_EQ(r.stats.rays_total, p.samples_u * p.samples_v) << what;
        EXPECT_EQ(r.stats.rays_hit, r.stats.rays_total) << what;
        EXPECT_EQ(r.stats.rays_filled, 0) << what;
        EXPECT_EQ(r.stats.stroke_rays_hit, r.stats.stroke_rays) << what;
        // (a) bottom vertices (w = 0) on the target surface
        double worst = 0;
        int bottom = 0;
        for (std::size_t i = 0; i < obj.positions.size(); ++i)
          if (r.binding.params[i].z == 0.0) {
            ++bottom;
            worst = std::max(worst, sc.distance(r.positions[i]));
          }
        EXPECT_GT(bottom, 50) << what;
        EXPECT_LE(worst, 1e-3 * sc.size) << what << " worst distance " << worst;
        // (c) orientation: det J > 0 and the closed object keeps a positive signed volume
        EXPECT_GT(r.stats.min_det_jacobian, 0.0) << what;
        EXPECT_GT(signed_volume(placed_mesh(obj, r)), 0.0) << what;
        for (double u : {0.1, 0.5, 0.9})
          for (double v : {0.0, 0.5, 1.0}) EXPECT_GT(jacobian_determinant(r.binding.lattice, {u, v, 0.5}), 0.0) << what;
        // the binding reproduces the returned positions through ffd_apply
        const TriMesh applied = ffd_apply(r.binding, obj);
        EXPECT_EQ(applied.positions, r.positions) << what;
        EXPECT_EQ(r.record.contact_points.size(), static_cast<std::size_t>(r.stats.rays_total));
      }
}

TEST(SketchPlacement, ExtrudeIsExactlyContactPlusHeightTowardViewer) {
  const TriMesh obj = object_box();
  const RayCaster rc = caster_for(height_field(5.0, 200, bumps));
  SketchPlacementParams p = default_params(curved_stroke());
  p.order[2] = 3;  // Greville layers keep F1 linear in w for any order
  p.controls[2] = 4;
  const SketchPlacementResult r = place_along_stroke(rc, p, obj.positions);
  const glm::dvec3 V = -p.camera.forward();
  for (double u : {0.0, 0.3, 0.77, 1.0})
    for (double v : {0.0, 0.4, 1.0})
      for (double w : {0.25, 1.0}) {
        const glm::dvec3 d = r.binding.lattice.eval({u, v, w}) - r.binding.lattice.eval({u, v, 0.0});
        EXPECT_LE(glm::length(d - w * p.height * V), 1e-12);
      }
}

TEST(SketchPlacement, OffsetTopFollowsSurfaceNormal) {
  const TriMesh obj = object_box();
  const double R = 4.0;
  TriMesh sphere = make_uv_sphere(R, 128, 256);
  for (auto& q : sphere.positions) q.y -= R;
  const RayCaster rc = caster_for(sphere);
  SketchPlacementParams p = default_params(straight_stroke());
  p.volume = PlacementVolume::Offset;
  const SketchPlacementResult r = place_along_stroke(rc, p, obj.positions);
  const glm::dvec3 c(0, -R, 0);
  double worst = 0;
  for (std::size_t i = 0; i < obj.positions.size(); ++i)
    if (r.binding.params[i].z == 1.0)
      worst = std::max(worst, std::abs(glm::length(r.positions[i] - c) - (R + p.height)));
  // Offsetting the control mesh approximates the offset surface (seed, after Eq. 2.4): a few % of h.
  EXPECT_LE(worst, 0.05 * p.height);
}

TEST(SketchPlacement, DeterministicBitIdentical) {
  const TriMesh obj = object_box();
  const RayCaster rc = caster_for(height_field(5.0, 200, bumps));
  const SketchPlacementParams p = default_params(curved_stroke());
  const auto a = place_along_stroke(rc, p, obj.positions);
  const auto b = place_along_stroke(rc, p, obj.positions);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::dvec3)), 0);
  const auto& ca = a.binding.lattice.control_points();
  const auto& cb = b.binding.lattice.control_points();
  ASSERT_EQ(ca.size(), cb.size());
  EXPECT_EQ(std::memcmp(ca.data(), cb.data(), ca.size() * sizeof(glm::dvec3)), 0);
  EXPECT_EQ(a.record.contact_points, b.record.contact_points);
}

TEST(SketchPlacement, PartialMissesAreFilledOnTheirRays) {
  // A 3×3 plane: the curved stroke's right end runs off its edge.
  const RayCaster rc = caster_for(height_field(1.5, 6, [](double, double) { return 0.0; }));
  SketchPlacementParams p = default_params(straight_stroke());
  p.stroke_px = {{440, 360}, {960, 360}};
  const auto r = place_along_stroke(rc, p, object_box().positions);
  EXPECT_GT(r.stats.rays_filled, 0);
  EXPECT_LT(r.stats.rays_filled, r.stats.rays_total / 2);
  EXPECT_EQ(r.stats.rays_hit + r.stats.rays_filled, r.stats.rays_total);
  for (std::size_t g = 0; g < r.record.contact_points.size(); ++g) {
    const glm::dvec3 q = r.record.contact_points[g];
    if (!r.record.contact_hit[g]) {
      EXPECT_NEAR(q.y, 0.0, 1e-9);  // constant view depth interpolated
    }
  }
}

TEST(SketchPlacement, ObliqueCameraOnTerrain) {
  const TriMesh obj = object_box();
  const TriMesh terrain = height_field(5.0, 200, bumps);
  const RayCaster rc = caster_for(terrain);
  for (auto vol : {PlacementVolume::Extrude, PlacementVolume::Offset}) {
    SketchPlacementParams p = default_params(curved_stroke());
    p.camera.eye = {1.0, 5.0, 5.0};  // looking down at ~45°: V = −forward is not the world up
    p.camera.up = {0.0, 1.0, 0.0};
    p.volume = vol;
    const auto r = place_along_stroke(rc, p, obj.positions);
    EXPECT_EQ(r.stats.rays_hit, r.stats.rays_total);
    double worst = 0;
    for (std::size_t i = 0; i < obj.positions.size(); ++i)
      if (r.binding.params[i].z == 0.0)
        worst = std::max(worst, std::abs(r.positions[i].y - bumps(r.positions[i].x, r.positions[i].z)));
    EXPECT_LE(worst, 1e-3 * std::sqrt(200.0));
    EXPECT_GT(r.stats.min_det_jacobian, 0.0);
    EXPECT_GT(signed_volume(placed_mesh(obj, r)), 0.0);
  }
}
