// lattice.ring and lattice.animate_offset through the registry and history, as a log replays them: the ring lattice
// is periodic along u, so moving an object by a whole period (or by the ring's symmetry) is exact.
#include <gtest/gtest.h>

#include <cmath>

#include "core/commands/lattice_ring.h"
#include "core/scene/scene.h"
#include "editor/command_registry.h"
#include "editor/history.h"

using namespace trispline;

namespace {

void run(editor::History& history, const nlohmann::json& line) {
  core::CommandContext ctx;
  history.execute(editor::CommandRegistry::builtin().parse(line, ctx));
}

double max_distance(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
  return d;
}

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

TEST_F(RingLattice, OneFullPeriodReturnsToTheStartAndAQuarterTurnIsARotation) {
  run(history, {{"cmd", "lattice.animate_offset"}, {"object", "t"}, {"velocity", {0.25, 0.0, 0.0}}});
  const std::vector<glm::dvec3> start = object().world_mesh->positions;
  const core::Scene full_turn = core::scene_at_time(scene, 4.0);  // offset 1 = one period
  EXPECT_LT(max_distance(full_turn.find("t")->world_mesh->positions, start), 1e-9);
  // 16 control points on a circle: an offset of 4/16 moves the control net onto itself turned by 90° about the
  // ring's axis (θ from +x towards +z), so the deformed object turns exactly, up to rounding.
  const core::Scene quarter = core::scene_at_time(scene, 1.0);
  std::vector<glm::dvec3> turned;
  for (const auto& p : start) turned.emplace_back(0.5 - (p.z + 0.25), p.y, -0.25 + (p.x - 0.5));
  EXPECT_LT(max_distance(quarter.find("t")->world_mesh->positions, turned), 1e-9);
  EXPECT_GT(max_distance(quarter.find("t")->world_mesh->positions, start), 0.5);  // it did move
  // The scene itself is untouched by scene_at_time, and undo restores the still object bit for bit.
  EXPECT_EQ(object().world_mesh->positions, start);
  history.undo();
  EXPECT_EQ(object().offset_velocity, glm::dvec3(0.0));
  EXPECT_EQ(object().world_mesh->positions, start);
}

TEST(RingLatticeFunction, RejectsBadSizes) {
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 0.2, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {3, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {5, 2, 2}), std::invalid_argument);
  EXPECT_NO_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}));
}

}  // namespace
