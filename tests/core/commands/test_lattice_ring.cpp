// lattice.ring through the registry and history, as a log replays it: the object sits on a periodic ring lattice
// (moving it along the ring: test_lattice_animate_offset.cpp); with twist_deg 180 (seed Fig. 4.6) on a Möbius band,
// upside down one turn later, its lattice certified fold-free; twists that are not quarter turns are refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/commands/lattice_ring.h"
#include "core/scene/scene.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/commands/history_test_util.h"

using namespace trispline;

namespace lattice_ring_test {

using test::run;

class RingLattice : public ::testing::Test {
 protected:
  void SetUp() override {
    run(history, {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}});
    run(history, {{"cmd", "lattice.ring"}, {"object", "t"}, {"center", {0.5, 0.1, -0.25}}, {"radius", 1.2}});
  }
  const core::SceneObject& object() const { return *scene.find("t"); }
  core::Scene scene;
  editor::History history{scene};
};

TEST_F(RingLattice, ObjectSitsOnTheRingAndKeepsItsHeight) {
  const core::SceneObject& o = object();
  ASSERT_TRUE(o.ffd);
  EXPECT_TRUE(o.ffd->lattice.knots(0).is_periodic());
  const core::TriMesh rest = o.world_rest_mesh();
  double min_y = 1e9, max_y = -1e9, rest_min = 1e9, rest_max = -1e9, mean_r = 0.0;
  for (const auto& p : o.world_mesh->positions) {
    min_y = std::min(min_y, p.y);
    max_y = std::max(max_y, p.y);
    mean_r += std::hypot(p.x - 0.5, p.z + 0.25);
  }
  for (const auto& p : rest.positions) {
    rest_min = std::min(rest_min, p.y);
    rest_max = std::max(rest_max, p.y);
  }
  mean_r /= static_cast<double>(o.world_mesh->positions.size());
  EXPECT_NEAR(min_y, 0.1, 1e-9);  // w = 0 is the ring's plane; w is linear (order 2), so heights map exactly
  EXPECT_NEAR(max_y - min_y, rest_max - rest_min, 1e-9);
  EXPECT_NEAR(mean_r, 1.2, 0.05 * 1.2);  // the object's middle follows the ring's centre line
}

// The teapot of RingLattice on a half-twisted ring (a Möbius band) of the same centre and radius.
const nlohmann::json kTwistedRing = {{"cmd", "lattice.ring"}, {"object", "t"},    {"center", {0.5, 0.1, -0.25}},
                                     {"radius", 1.2},         {"twist_deg", 180}, {"controls", {32, 2, 2}}};

class TwistedRingLattice : public ::testing::Test {
 protected:
  void SetUp() override {
    run(history, {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}});
    run(history, {{"cmd", "lattice.ring"}, {"object", "t"}, {"center", {0.5, 0.1, -0.25}}, {"radius", 1.2}});
    untwisted = history.last_executed().stats();
    run(history, kTwistedRing);
    twisted = history.last_executed().stats();
  }
  const core::SceneObject& object() const { return *scene.find("t"); }
  core::Scene scene;
  editor::History history{scene};
  nlohmann::json untwisted, twisted;  // report.json statistics of the two lattice.ring lines
};

TEST_F(TwistedRingLattice, SpansTwoTurnsKeepsItsProportionsAndIsFinite) {
  const core::SceneObject& o = object();
  ASSERT_TRUE(o.ffd);
  EXPECT_TRUE(o.ffd->lattice.knots(0).is_periodic());
  EXPECT_EQ(twisted.at("laps"), 2);
  EXPECT_EQ(untwisted.at("laps"), 1);
  // One period is two turns, so the object's default span is half the untwisted one: the same length in world units.
  EXPECT_DOUBLE_EQ(twisted.at("span").get<double>(), 0.5 * untwisted.at("span").get<double>());
  EXPECT_EQ(twisted.at("vertices"), o.world_rest_mesh().positions.size());
  ASSERT_FALSE(o.world_mesh->positions.empty());
  for (const glm::dvec3& p : o.world_mesh->positions)
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  test::run(history, {{"cmd", "lattice.certify"}, {"object", "t"}});
  EXPECT_EQ(history.last_executed().stats().at("certificate"), "fold_free");  // det J > 0: the twist is a rotation
}

// Half a period (one turn) later the object is at the same place round the ring, upside down beneath the band: every
// vertex is as far below the band's centre plane y = center.y as it was above it (the lattice's cross-sections there
// are the first turn's turned by 180° about the centre line, which stays in that plane).
TEST_F(TwistedRingLattice, OneTurnLaterTheObjectIsUpsideDownBeneathTheBand) {
  const std::vector<glm::dvec3> start = object().world_mesh->positions;
  test::run(history, {{"cmd", "lattice.animate_offset"}, {"object", "t"}, {"offset", {0.5, 0.0, 0.0}}});
  const std::vector<glm::dvec3>& later = object().world_mesh->positions;
  ASSERT_EQ(later.size(), start.size());
  double worst = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    worst = std::max(worst, std::abs((later[i].y - 0.1) + (start[i].y - 0.1)));
    moved = std::max(moved, glm::length(later[i] - start[i]));
  }
  EXPECT_LT(worst, 1e-10);  // rounding only: coordinates are ~1 world unit
  EXPECT_GT(moved, 0.1);    // it did turn over
}

TEST_F(TwistedRingLattice, TwistsThatAreNotQuarterTurnsAreRefusedByNameAndChangeNothing) {
  const std::vector<glm::dvec3> before = object().world_mesh->positions;
  const std::size_t steps = history.size();
  const auto with = [](const char* key, nlohmann::json value) {
    nlohmann::json line = kTwistedRing;
    line[key] = std::move(value);
    return line;
  };
  EXPECT_TRUE(test::throws_command_error([&] { run(history, with("twist_deg", 45)); }, "twist_deg", "multiple of 90"));
  EXPECT_TRUE(test::throws_command_error([&] { run(history, with("twist_deg", 1000)); }, "twist_deg", "720"));
  // Two turns per period: the control points around must split evenly between them.
  const nlohmann::json uneven = with("controls", {33, 2, 2});
  EXPECT_TRUE(test::throws_command_error([&] { run(history, uneven); }, "controls", "multiple of 2"));
  // The turning cross-section must stay clear of the ring's axis: radius > hypot(width/2, height).
  nlohmann::json narrow = with("radius", 0.38);  // > width/2 = 0.25, < hypot(0.25, 0.3) = 0.39
  narrow["width"] = 0.5;
  narrow["height"] = 0.3;
  EXPECT_TRUE(test::throws_command_error([&] { run(history, narrow); }, "radius", "hypot"));
  EXPECT_EQ(history.size(), steps);
  EXPECT_EQ(object().world_mesh->positions, before);
}

}  // namespace lattice_ring_test
