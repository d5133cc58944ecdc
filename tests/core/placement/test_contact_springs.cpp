// Mass-spring relaxation of the contact surface (seed §2.3.2): bridging a gap between two boxes, a flat grid stays
// put, determinism, bad parameters throw.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/placement/contact_springs.h"
#include "placement_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

constexpr double kBoxTop = 1.0;
constexpr int kL = 14, kM = 5;

TriMesh append(TriMesh a, const TriMesh& b) {
  const auto base = static_cast<unsigned>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (auto t : b.triangles) a.triangles.emplace_back(t.x + base, t.y + base, t.z + base);
  return a;
}

// Two boxes 1.5 × 1 × 2 (x ∈ [−2,−0.5] and [0.5,2], y ∈ [0,1], z ∈ [−1,1]) on a floor plane y = 0 (the gap floor).
TriMesh two_boxes_scene() {
  TriMesh s = height_field(4.0, 8, [](double, double) { return 0.0; });
  s = append(s, tessellated_box({1.5, kBoxTop, 2.0}, {-2.0, 0.0, -1.0}, 4));
  s = append(s, tessellated_box({1.5, kBoxTop, 2.0}, {0.5, 0.0, -1.0}, 4));
  return s;
}

double column_x(int i) { return -1.95 + 0.3 * i; }
bool over_gap(int i) { return std::abs(column_x(i)) < 0.5; }

// 14 × 5 grid, x = −1.95..1.95 (columns 5..8 over the gap), z = −0.8..0.8; every point on the surface below it.
std::vector<glm::dvec3> bridging_grid() {
  std::vector<glm::dvec3> p;
  for (int j = 0; j < kM; ++j)
    for (int i = 0; i < kL; ++i) p.emplace_back(column_x(i), over_gap(i) ? 0.0 : kBoxTop, -0.8 + 0.4 * j);
  return p;
}

std::vector<glm::dvec3> up(size_t n) { return std::vector<glm::dvec3>(n, glm::dvec3(0, 1, 0)); }

SpringParams bridging_params() {
  SpringParams sp;
  sp.mass = 1.0;
  sp.stiffness = 50.0;
  sp.damping = 20.0;  // = sqrt(8kM): overdamped, dt = M/ρ (discrete maximum principle, see contact_springs.h)
  sp.angle_threshold_deg = 2.0;
  sp.neighbourhood = -1;
  sp.max_steps = 20000;
  sp.ray_height = 10.0;
  return sp;
}

// Floor along +y under p, as the relaxation computes it (ray from p + H·y down).
std::optional<double> floor_y(const RayCaster& rc, const glm::dvec3& p, double H) {
  const auto hit = rc.intersect(p + glm::dvec3(0, H, 0), {0, -1, 0});
  if (!hit) return std::nullopt;
  return hit->position.y;
}

}  // namespace

TEST(ContactSprings, BridgesGapBetweenBoxes) {
  const TriMesh scene = two_boxes_scene();
  const RayCaster rc = caster_for(scene);
  std::vector<glm::dvec3> p = bridging_grid();
  const std::vector<glm::dvec3> p0 = p;
  const SpringParams sp = bridging_params();
  const SpringStats st = relax_contact_surface(p, kL, kM, up(p.size()), &rc, sp);
  EXPECT_TRUE(st.converged) << "steps " << st.steps;
  EXPECT_GT(st.steps, 0);
  EXPECT_EQ(st.floors, kL * kM);
  EXPECT_EQ(st.active, kL * kM);
  EXPECT_GT(st.max_displacement, 0.8 * kBoxTop);
  for (int j = 0; j < kM; ++j)
    for (int i = 0; i < kL; ++i) {
      const glm::dvec3& q = p[i + kL * j];
      // Only the y coordinate moves.
      EXPECT_EQ(q.x, p0[i + kL * j].x);
      EXPECT_EQ(q.z, p0[i + kL * j].z);
      const auto f = floor_y(rc, p0[i + kL * j], sp.ray_height);
      ASSERT_TRUE(f.has_value());
      EXPECT_GE(q.y, *f - 1e-9) << "mass " << i << "," << j << " below its floor";
      if (!over_gap(i)) {
        EXPECT_NEAR(q.y, kBoxTop, 1e-9) << "outer mass " << i << "," << j << " left its support";
      } else {
        EXPECT_GE(q.y, 0.8 * kBoxTop) << "middle mass " << i << "," << j << " did not rise";
      }
    }
}

TEST(ContactSprings, NeighbourhoodLimitsMovingMasses) {
  const RayCaster rc = caster_for(two_boxes_scene());
  std::vector<glm::dvec3> p = bridging_grid();
  const std::vector<glm::dvec3> p0 = p;
  SpringParams sp = bridging_params();
  sp.neighbourhood = 1;  // candidates: columns 4,5,8,9 (the kinks) → active columns 3..10
  const SpringStats st = relax_contact_surface(p, kL, kM, up(p.size()), &rc, sp);
  EXPECT_EQ(st.candidates, 4 * kM);
  EXPECT_EQ(st.active, 8 * kM);
  EXPECT_TRUE(st.converged);
  for (int j = 0; j < kM; ++j)
    for (int i = 0; i < kL; ++i) {
      const glm::dvec3& q = p[i + kL * j];
      if (i < 3 || i > 10) {
        EXPECT_EQ(q, p0[i + kL * j]);
      }
      if (over_gap(i)) {
        EXPECT_GE(q.y, 0.8 * kBoxTop);
      } else {
        EXPECT_NEAR(q.y, kBoxTop, 1e-9);
      }
    }
}

TEST(ContactSprings, FlatGridStaysPut) {
  const RayCaster rc = caster_for(height_field(4.0, 8, [](double, double) { return 0.0; }));
  std::vector<glm::dvec3> p;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 7; ++i) p.emplace_back(-1.5 + 0.5 * i, 0.0, -1.2 + 0.5 * j);
  const std::vector<glm::dvec3> p0 = p;
  const SpringStats st = relax_contact_surface(p, 7, 6, up(p.size()), &rc, bridging_params());
  EXPECT_TRUE(st.converged);
  EXPECT_LE(st.steps, 1);
  EXPECT_EQ(st.candidates, 0);
  EXPECT_LE(st.max_displacement, 1e-9);
  for (size_t a = 0; a < p.size(); ++a) EXPECT_NEAR(glm::length(p[a] - p0[a]), 0.0, 1e-9);
}

TEST(ContactSprings, RestLengthOptionStaysAboveFloors) {
  const RayCaster rc = caster_for(two_boxes_scene());
  std::vector<glm::dvec3> p = bridging_grid();
  const std::vector<glm::dvec3> p0 = p;
  SpringParams sp = bridging_params();
  sp.rest_length_initial = true;
  sp.max_steps = 3000;
  const SpringStats st = relax_contact_surface(p, kL, kM, up(p.size()), &rc, sp);
  EXPECT_GT(st.steps, 0);
  for (size_t a = 0; a < p.size(); ++a) {
    ASSERT_TRUE(std::isfinite(p[a].y));
    EXPECT_GE(p[a].y, *floor_y(rc, p0[a], sp.ray_height) - 1e-9);
  }
}

TEST(ContactSprings, Deterministic) {
  const RayCaster rc = caster_for(two_boxes_scene());
  std::vector<glm::dvec3> a = bridging_grid(), b = bridging_grid();
  const SpringStats sa = relax_contact_surface(a, kL, kM, up(a.size()), &rc, bridging_params());
  const SpringStats sb = relax_contact_surface(b, kL, kM, up(b.size()), &rc, bridging_params());
  EXPECT_EQ(sa.steps, sb.steps);
  EXPECT_EQ(sa.converged, sb.converged);
  EXPECT_EQ(std::memcmp(&sa.max_displacement, &sb.max_displacement, sizeof(double)), 0);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::dvec3)), 0);
}

TEST(ContactSprings, BadParamsThrow) {
  std::vector<glm::dvec3> p = bridging_grid();
  const auto dirs = up(p.size());
  auto throws = [&](auto mutate) {
    SpringParams sp = bridging_params();
    mutate(sp);
    std::vector<glm::dvec3> q = p;
    EXPECT_THROW(relax_contact_surface(q, kL, kM, dirs, nullptr, sp), std::invalid_argument);
  };
  throws([](SpringParams& s) { s.mass = 0.0; });
  throws([](SpringParams& s) { s.mass = -1.0; });
  throws([](SpringParams& s) { s.stiffness = 0.0; });
  throws([](SpringParams& s) { s.stiffness = -3.0; });
  throws([](SpringParams& s) { s.damping = -0.1; });
  throws([](SpringParams& s) { s.angle_threshold_deg = 0.0; });
  throws([](SpringParams& s) { s.angle_threshold_deg = 180.0; });
  throws([](SpringParams& s) { s.angle_threshold_deg = -5.0; });
  throws([](SpringParams& s) { s.max_steps = -1; });
  throws([](SpringParams& s) { s.ray_height = 0.0; });
  // Shape errors.
  std::vector<glm::dvec3> q = p;
  EXPECT_THROW(relax_contact_surface(q, kL + 1, kM, dirs, nullptr, bridging_params()), std::invalid_argument);
  EXPECT_THROW(relax_contact_surface(q, 0, kM, dirs, nullptr, bridging_params()), std::invalid_argument);
  EXPECT_THROW(relax_contact_surface(q, kL, kM, up(3), nullptr, bridging_params()), std::invalid_argument);
  auto bad_dirs = dirs;
  bad_dirs[5] = {0, 2, 0};
  EXPECT_THROW(relax_contact_surface(q, kL, kM, bad_dirs, nullptr, bridging_params()), std::invalid_argument);
  // No scene: valid, nothing thrown.
  EXPECT_NO_THROW(relax_contact_surface(q, kL, kM, dirs, nullptr, bridging_params()));
}

TEST(ContactSprings, DefaultParamsBridge) {
  const RayCaster rc = caster_for(two_boxes_scene());
  std::vector<glm::dvec3> p = bridging_grid();
  SpringParams sp;  // defaults: overdamped
  sp.ray_height = 10.0;
  const SpringStats st = relax_contact_surface(p, kL, kM, up(p.size()), &rc, sp);
  EXPECT_TRUE(st.converged);
  double lo = 1e9;
  for (int j = 0; j < kM; ++j)
    for (int i = 0; i < kL; ++i) {
      if (over_gap(i))
        lo = std::min(lo, p[i + kL * j].y);
      else {
        EXPECT_NEAR(p[i + kL * j].y, kBoxTop, 1e-9);
      }
    }
  EXPECT_GE(lo, 0.8 * kBoxTop);
}
