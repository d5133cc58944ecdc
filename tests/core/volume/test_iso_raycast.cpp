// Iso-surface ray casting on the spline (core/volume/iso_raycast.h) against analytic surfaces: signed distance
// fields of a sphere and a torus sampled on oblique, anisotropic grids (iso_test_volumes.h), interpolated by the
// spline, so the hits lie on the exact surfaces within the spline's approximation error (measured and printed);
// normals are the surfaces' outward normals; rays that miss, start inside, or stop short behave; brick skipping
// changes no result; the pixel rays go through their pixel centres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <stdexcept>
#include <string>

#include "core/volume/iso_raycast.h"
#include "core/volume/volume_spline.h"
#include "tests/core/volume/iso_test_volumes.h"

namespace trispline::core {
namespace {

using test::sphere_volume;
using test::torus_volume;

glm::dvec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-6) return glm::normalize(v);
  }
}

// Near intersection parameter of origin + t·dir with a sphere (dir unit), or NaN.
double ray_sphere(const glm::dvec3& o, const glm::dvec3& dir, const glm::dvec3& c, double r) {
  const glm::dvec3 q = o - c;
  const double b = glm::dot(q, dir), disc = b * b - (glm::dot(q, q) - r * r);
  return disc < 0.0 ? std::nan("") : -b - std::sqrt(disc);
}

// Rays from 60 mm away aimed at points inside the sphere (0.7 r from the centre, so never grazing): every ray hits
// the near side of the sphere within `tol` mm, with the outward radial normal; t and the index point agree with the
// world point. Returns the largest distance from the exact sphere.
double check_sphere_hits(const VolumeSpline& spline, const test::SphereField& f, double tol, const char* what) {
  std::mt19937 rng(7);
  double worst = 0.0, worst_normal = 0.0;
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 target = f.center + 0.7 * f.radius * random_unit(rng);
    const glm::dvec3 origin = f.center + 60.0 * random_unit(rng);
    const glm::dvec3 dir = 2.5 * (target - origin);  // not unit on purpose
    const IsoHit h = iso_ray_hit(spline, 0.0, origin, dir);
    EXPECT_TRUE(h.hit) << what << " ray " << k;
    if (!h.hit) continue;
    const double err = std::abs(glm::length(h.world_point - f.center) - f.radius);
    worst = std::max(worst, err);
    EXPECT_LE(err, tol) << what << " ray " << k;
    // The near intersection, not the far one.
    const glm::dvec3 u = glm::normalize(dir);
    const double t_near = ray_sphere(origin, u, f.center, f.radius);
    EXPECT_LE(glm::length(h.world_point - (origin + t_near * u)), 2.0 * tol) << what << " ray " << k;
    EXPECT_NEAR(glm::length(h.world_point - (origin + h.t * dir)), 0.0, 1e-9 * glm::length(origin));
    const glm::dvec3 w = glm::dvec3(spline.index_to_world() * glm::dvec4(h.index_point, 1.0));
    EXPECT_NEAR(glm::length(w - h.world_point), 0.0, 1e-9);
    EXPECT_NEAR(spline.value(h.index_point), 0.0, 1e-7) << what;
    EXPECT_NEAR(glm::length(h.world_normal), 1.0, 1e-12);
    const double dn = glm::length(h.world_normal - glm::normalize(h.world_point - f.center));
    worst_normal = std::max(worst_normal, dn);
  }
  std::printf("[iso sphere] %-28s max |dist − r| = %.3g mm, max |n − radial| = %.3g\n", what, worst, worst_normal);
  EXPECT_LE(worst_normal, 20.0 * tol / f.radius) << what;
  return worst;
}

TEST(IsoRaycast, CubicInterpolatingSphereHitsTheExactSphere) {
  const auto s = sphere_volume();
  const VolumeSpline spline(s.volume, 4, true);
  check_sphere_hits(spline, s.field, 1e-3, "order 4, interpolating");
}

TEST(IsoRaycast, LowerOrdersAndApproximationStayNearTheSphere) {
  const auto s = sphere_volume();
  // Measured: order 3 interpolating ≈ 2e-4 mm, trilinear ≈ 0.024 mm (the SDF's curvature between samples), order 4
  // on the raw samples ≈ 0.034 mm (the approximating spline shrinks the sphere by ~h²κ/6).
  check_sphere_hits(VolumeSpline(s.volume, 3, true), s.field, 1e-3, "order 3, interpolating");
  check_sphere_hits(VolumeSpline(s.volume, 2, false), s.field, 5e-2, "order 2 (trilinear)");
  check_sphere_hits(VolumeSpline(s.volume, 4, false), s.field, 6e-2, "order 4, approximating");
}

TEST(IsoRaycast, RaysThatMissReportNoHit) {
  const auto s = sphere_volume();
  const VolumeSpline spline(s.volume, 4, true);
  std::mt19937 rng(11);
  for (int k = 0; k < 50; ++k) {
    // A line passing 2 mm outside the sphere (through the grid box: the box half-extent exceeds r + 2 everywhere).
    const glm::dvec3 dir = random_unit(rng);
    glm::dvec3 side = glm::normalize(glm::cross(dir, random_unit(rng)));
    const glm::dvec3 closest = s.field.center + (s.field.radius + 2.0) * side;
    const IsoHit h = iso_ray_hit(spline, 0.0, closest - 50.0 * dir, dir);
    EXPECT_FALSE(h.hit) << k;
    EXPECT_EQ(h.t, 0.0);
    EXPECT_EQ(h.world_normal, glm::dvec3(0.0));
  }
  // Pointing away from the volume; stopping (t_max) before the surface; a ray beside the box.
  const glm::dvec3 out = s.field.center + glm::dvec3(0.0, 0.0, 80.0);
  EXPECT_FALSE(iso_ray_hit(spline, 0.0, out, {0.0, 0.0, 1.0}).hit);
  const double before = 80.0 - s.field.radius - 0.5;
  EXPECT_FALSE(iso_ray_hit(spline, 0.0, out, {0.0, 0.0, -1.0}, 0.25, before).hit);
  EXPECT_TRUE(iso_ray_hit(spline, 0.0, out, {0.0, 0.0, -1.0}, 0.25, before + 1.0).hit);
  EXPECT_FALSE(iso_ray_hit(spline, 0.0, out + glm::dvec3(200.0, 0.0, 0.0), {0.0, 0.0, -1.0}).hit);
  // An iso-level no sample reaches.
  EXPECT_FALSE(iso_ray_hit(spline, 1e3, out, {0.0, 0.0, -1.0}).hit);
}

TEST(IsoRaycast, RayStartingInsideHitsWhereItLeaves) {
  const auto s = sphere_volume();
  const VolumeSpline spline(s.volume, 4, true);
  std::mt19937 rng(3);
  for (int k = 0; k < 20; ++k) {
    const glm::dvec3 dir = random_unit(rng);
    const glm::dvec3 origin = s.field.center + 0.3 * s.field.radius * random_unit(rng);
    const IsoHit h = iso_ray_hit(spline, 0.0, origin, dir);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(glm::length(h.world_point - s.field.center), s.field.radius, 1e-3);
    EXPECT_GT(glm::dot(h.world_normal, dir), 0.0);  // outward normal, the ray leaving
  }
}

TEST(IsoRaycast, TorusHitsAndItsHoleIsEmpty) {
  const auto tv = torus_volume();
  const test::TorusField& f = tv.field;
  const VolumeSpline spline(tv.volume, 4, true);
  // Along the axis through the hole: nothing.
  EXPECT_FALSE(iso_ray_hit(spline, 0.0, f.center + 40.0 * f.axis, -f.axis).hit);
  // In the torus plane from outside towards the centre: the outer equator at major + minor.
  const glm::dvec3 radial = glm::normalize(glm::cross(f.axis, glm::dvec3(0.3, 1.0, 0.2)));
  const IsoHit outer = iso_ray_hit(spline, 0.0, f.center + 40.0 * radial, -radial);
  ASSERT_TRUE(outer.hit);
  EXPECT_NEAR(glm::length(outer.world_point - f.center), f.major + f.minor, 1e-3);
  EXPECT_GT(glm::dot(outer.world_normal, radial), 1.0 - 1e-4);
  // From the centre outwards: the inner equator at major − minor.
  const IsoHit inner = iso_ray_hit(spline, 0.0, f.center, radial);
  ASSERT_TRUE(inner.hit);
  EXPECT_NEAR(glm::length(inner.world_point - f.center), f.major - f.minor, 1e-3);
  EXPECT_LT(glm::dot(inner.world_normal, radial), -1.0 + 1e-4);
  // Oblique rays at points of the tube: on the torus, normals the torus's.
  std::mt19937 rng(5);
  double worst = 0.0, worst_n = 0.0;
  int hits = 0;
  for (int k = 0; k < 150; ++k) {
    const glm::dvec3 q = random_unit(rng);
    const glm::dvec3 in_plane = glm::normalize(q - glm::dot(q, f.axis) * f.axis);
    const glm::dvec3 target = f.center + f.major * in_plane + 0.5 * f.minor * random_unit(rng);
    const glm::dvec3 origin = f.center + 50.0 * random_unit(rng);
    const IsoHit h = iso_ray_hit(spline, 0.0, origin, target - origin);
    ASSERT_TRUE(h.hit) << k;  // the ray reaches a point inside the tube, so it crosses the surface first
    ++hits;
    worst = std::max(worst, std::abs(f(h.world_point)));
    worst_n = std::max(worst_n, glm::length(h.world_normal - f.outward_normal(h.world_point)));
  }
  std::printf("[iso torus] %d hits: max |sdf| = %.3g mm, max |n − n_exact| = %.3g\n", hits, worst, worst_n);
  EXPECT_LE(worst, 1e-3);
  EXPECT_LE(worst_n, 1e-3);
}

// Control points weighing D somewhere on the index interval (lo, hi) of one axis: the centred basis function of
// control i is nonzero on (i − k/2, i + k/2); indices outside the grid stand for the nearest boundary control.
std::array<int, 2> support_of(double lo, double hi, int order, int n) {
  const int first = int(std::floor(lo - 0.5 * order)) + 1, last = int(std::ceil(hi + 0.5 * order)) - 1;
  return {std::clamp(first, 0, n - 1), std::clamp(last, 0, n - 1)};
}

// Bricks bound D (convex hull) and ∂D (the slope), tightly: their ranges are the min / max of exactly the control
// points whose basis functions reach into the brick. Skipping (bricks and slope) gives the same hits bit for bit: the
// torus (two surfaces along many rays, few bricks away from the surface) and a 64³ sphere (most bricks empty).
TEST(IsoRaycast, RangeGridBoundsTheSplineAndSkippingChangesNothing) {
  const auto tv = torus_volume();
  const auto sv = sphere_volume({64, 64, 64});
  struct Case {
    const char* name;
    const ScalarVolume* volume;
    glm::dvec3 center;
    double ray_radius;  // rays aim at points within this distance of the centre (mm)
  };
  for (const Case& c :
       {Case{"torus", &tv.volume, tv.field.center, 18.0}, Case{"sphere 64", &sv.volume, sv.field.center, 14.0}})
    for (int order = 2; order <= 4; ++order) {
      const VolumeSpline spline(*c.volume, order, order > 2);
      const std::array<int, 3>& n = spline.dims();
      for (int brick : {1, 2, 4, 7}) {
        SCOPED_TRACE(std::string(c.name) + " order " + std::to_string(order) + " brick " + std::to_string(brick));
        const VolumeRangeGrid grid = build_volume_range_grid(spline, brick);
        for (int a = 0; a < 3; ++a) EXPECT_EQ(grid.dims[a], (n[a] - 1 + brick - 1) / brick);
        ASSERT_EQ(grid.slope.size(), grid.range.size());
        // Tight: every brick's range is the min / max of its support's control points; its slope the largest
        // neighbour difference from a support control (a superset of the support's own pairs).
        for (int bz = 0; bz < grid.dims[2]; bz += 3)
          for (int by = 0; by < grid.dims[1]; by += 2)
            for (int bx = 0; bx < grid.dims[0]; ++bx) {
              std::array<std::array<int, 2>, 3> sup;
              const int b[3] = {bx, by, bz};
              for (int a = 0; a < 3; ++a)
                sup[a] = support_of(brick * b[a], std::min(brick * (b[a] + 1), n[a] - 1), order, n[a]);
              float lo = 1e30f, hi = -1e30f;
              double slope = 0.0;
              for (int z = sup[2][0]; z <= sup[2][1]; ++z)
                for (int y = sup[1][0]; y <= sup[1][1]; ++y)
                  for (int x = sup[0][0]; x <= sup[0][1]; ++x) {
                    const float v = spline.control(x, y, z);
                    lo = std::min(lo, v), hi = std::max(hi, v);
                    for (glm::ivec3 e : {glm::ivec3(1, 0, 0), glm::ivec3(0, 1, 0), glm::ivec3(0, 0, 1)})
                      slope = std::max(slope, std::abs(double(spline.control(x + e.x, y + e.y, z + e.z)) - v));
                  }
              ASSERT_EQ(grid.at(bx, by, bz), glm::vec2(lo, hi)) << bx << " " << by << " " << bz;
              const float s = grid.slope[grid.index(bx, by, bz)];  // the double difference rounded up
              ASSERT_GE(double(s), slope) << bx << " " << by << " " << bz;
              ASSERT_LE(double(s), slope * (1.0 + 0x1p-22)) << bx << " " << by << " " << bz;
            }
        // Conservative: D and ∂D at random points (and brick corners) within their brick's bounds.
        std::mt19937 rng(order * 10 + brick);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const glm::dvec3 hi(n[0] - 1, n[1] - 1, n[2] - 1);
        int excluded = 0;
        for (int k = 0; k < 4000; ++k) {
          glm::dvec3 p = glm::dvec3(unit(rng), unit(rng), unit(rng)) * hi;
          if (k % 4 == 0) p = glm::min(glm::floor(p / double(brick)) * double(brick), hi);
          const auto b = grid.brick_of(p);
          const glm::vec2 r = grid.at(b[0], b[1], b[2]);
          const VolumeJet j = spline.jet(p);
          ASSERT_GE(j.value, double(r.x) - 1e-6);
          ASSERT_LE(j.value, double(r.y) + 1e-6);
          // (At corners the one-sided derivative of order 2 is the next brick's: D is Lipschitz, not C¹, there.)
          const double slope = grid.slope[grid.index(b[0], b[1], b[2])];
          for (int a = 0; a < 3 && k % 4 != 0; ++a) ASSERT_LE(std::abs(j.gradient[a]), slope * (1.0 + 1e-9) + 1e-9);
          excluded += (r.x > 0.0f || r.y < 0.0f);
        }
        if (c.volume == &sv.volume && brick <= 4) {
          EXPECT_GT(excluded, 2000) << "most bricks of the sphere exclude 0";
        }
        // The same hits, bit for bit, with and without skipping (rays from everywhere, hits and misses; a step of
        // 0.1 too, where the slope skips most samples).
        std::mt19937 rr(42 + brick);
        int hits = 0;
        for (int k = 0; k < 150; ++k) {
          const glm::dvec3 origin = c.center + 45.0 * random_unit(rr);
          const glm::dvec3 target = c.center + c.ray_radius * random_unit(rr);
          const double step = k % 3 == 0 ? 0.1 : 0.25;
          const IsoHit a = iso_ray_hit(spline, 0.0, origin, target - origin, step);
          const IsoHit b = iso_ray_hit(spline, 0.0, origin, target - origin, step, 1e300, &grid);
          ASSERT_EQ(a.hit, b.hit) << k;
          EXPECT_EQ(a.t, b.t) << k;
          hits += a.hit;
        }
        EXPECT_GT(hits, 30);
        EXPECT_LT(hits, 150);
      }
    }
  EXPECT_THROW(build_volume_range_grid(VolumeSpline(tv.volume, 4), 0), std::invalid_argument);
}

TEST(IsoRaycast, PixelRaysGoThroughTheirPixelCentres) {
  const glm::dmat4 view = glm::lookAt(glm::dvec3(10.0, 20.0, 90.0), glm::dvec3(-5.0, 5.0, 20.0), glm::dvec3(0, 1, 0));
  const glm::ivec4 viewport(3, 5, 64, 48);
  for (const glm::dmat4& proj : {glm::perspective(glm::radians(40.0), 64.0 / 48.0, 0.01, 1000.0),
                                 glm::ortho(-30.0, 30.0, -20.0, 25.0, 1.0, 300.0)}) {
    for (glm::ivec2 px : {glm::ivec2(3, 5), glm::ivec2(40, 30), glm::ivec2(66, 52)}) {
      const PixelRay r = pixel_ray(view, proj, viewport, px.x, px.y);
      for (double t : {0.0, 1.0, 500.0}) {
        const glm::dvec3 w = glm::project(r.origin + t * r.direction, view, proj, glm::dvec4(viewport));
        EXPECT_NEAR(w.x, px.x + 0.5, 1e-6);
        EXPECT_NEAR(w.y, px.y + 0.5, 1e-6);
      }
      const glm::dvec3 w0 = glm::project(r.origin, view, proj, glm::dvec4(viewport));
      EXPECT_NEAR(w0.z, 0.0, 1e-6);  // on the near plane
    }
  }
}

// A small image of the sphere: the hit mask is the exact sphere's except for rays passing within 0.05 mm of its
// silhouette; hit depths are the projected hit points; misses have depth 1.
TEST(IsoRaycast, CpuImageMatchesTheExactSphere) {
  const auto s = sphere_volume();
  const VolumeSpline spline(s.volume, 4, true);
  const VolumeRangeGrid grid = build_volume_range_grid(spline);
  const glm::dmat4 view = glm::lookAt(s.field.center + glm::dvec3(20.0, 30.0, 70.0), s.field.center, {0, 1, 0});
  const glm::dmat4 proj = glm::perspective(glm::radians(30.0), 1.0, 1.0, 500.0);
  const int n = 48;
  const IsoHitImage img = render_iso_hits_cpu(spline, 0.0, view, proj, n, n, 0.25, &grid);
  ASSERT_EQ(img.hits.size(), std::size_t(n * n));
  int hits = 0, band = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::size_t i = std::size_t(x + n * y);
      const PixelRay r = pixel_ray(view, proj, {0, 0, n, n}, x, y);
      const glm::dvec3 u = glm::normalize(r.direction);
      const glm::dvec3 q = s.field.center - r.origin;
      const double miss_distance = glm::length(q - glm::dot(q, u) * u) - s.field.radius;
      if (std::abs(miss_distance) < 0.05) {
        ++band;
        continue;
      }
      ASSERT_EQ(img.hits[i].hit, miss_distance < 0.0) << x << "," << y;
      if (!img.hits[i].hit) {
        EXPECT_EQ(img.depth[i], 1.0);
        continue;
      }
      ++hits;
      const glm::dvec3 w = glm::project(img.hits[i].world_point, view, proj, glm::dvec4(0, 0, n, n));
      EXPECT_NEAR(w.z, img.depth[i], 1e-12);
      EXPECT_NEAR(w.x, x + 0.5, 1e-6);
    }
  EXPECT_GT(hits, n * n / 8);
  EXPECT_LT(band, n);
}

TEST(IsoRaycast, BadArgumentsThrow) {
  const auto s = sphere_volume({8, 8, 8});
  const VolumeSpline spline(s.volume, 4);
  const glm::dvec3 o(0.0), d(0.0, 0.0, 1.0);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, glm::dvec3(0.0)), std::invalid_argument);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, glm::dvec3(NAN, 0.0, 0.0), d), std::invalid_argument);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, glm::dvec3(INFINITY, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, d, 0.0), std::invalid_argument);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, d, -1.0), std::invalid_argument);
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, d, 0.25, -1.0), std::invalid_argument);
  const auto big = sphere_volume({12, 8, 8});
  const VolumeRangeGrid other = build_volume_range_grid(VolumeSpline(big.volume, 4));
  EXPECT_THROW(iso_ray_hit(spline, 0.0, o, d, 0.25, 1.0, &other), std::invalid_argument);
  EXPECT_THROW(render_iso_hits_cpu(spline, 0.0, glm::dmat4(1.0), glm::dmat4(1.0), 0, 4), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
