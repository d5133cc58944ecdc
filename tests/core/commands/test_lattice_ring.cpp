// lattice.ring through the registry and history, as a log replays it: the object sits on a periodic ring lattice
// (moving it along the ring: test_lattice_animate_offset.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "core/commands/lattice_ring.h"
#include "core/scene/scene.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
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

}  // namespace lattice_ring_test
