// lattice.press and lattice.pull_column through the registry and history (as a log replays them): only control
// points inside the swept sphere move, each by strength × falloff along its column direction V_P; undo restores the
// lattice exactly; bad parameters leave the scene untouched.
#include <gtest/gtest.h>

#include "core/commands/lattice_press.h"
#include "core/commands/lattice_pull_column.h"
#include "core/scene/scene.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/history_test_util.h"

using namespace trispline;

namespace lattice_press_test {

using test::run;

class Pressing : public ::testing::Test {
 protected:
  void SetUp() override {
    run(history, {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}});
    // A ring lattice with 4 control points per column (order 2 in w): columns are vertical, V_P = +y.
    run(history,
        {{"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}});
  }
  const core::TrivariateBSpline<glm::dvec3>& lattice() const { return scene.find("t")->ffd->lattice; }
  core::Scene scene;
  editor::History history{scene};
};

TEST_F(Pressing, EachFalloffMovesOnlyPointsInsideBySphereWeightAlongTheColumn) {
  for (std::string_view name : core::kFalloffNames) {
    const core::TrivariateBSpline<glm::dvec3> before = lattice();
    const std::vector<glm::dvec3> mesh_before = scene.find("t")->world_mesh->positions;
    // Centre the sphere near the top control point of column (0, 1); sweep it a little along the ring.
    const glm::dvec3 c0 = before.control_point(0, 1, 3) + glm::dvec3(0.0, 0.02, 0.0);
    const glm::dvec3 c1 = c0 + glm::dvec3(0.0, 0.0, 0.05);
    const double radius = 0.5, strength = 0.04;
    run(history, {{"cmd", "lattice.press"},
                  {"object", "t"},
                  {"path", {{c0.x, c0.y, c0.z}, {c1.x, c1.y, c1.z}}},
                  {"radius", radius},
                  {"strength", strength},
                  {"falloff", std::string(name)}});
    const auto f = *core::parse_falloff(name);
    const glm::ivec3 n = before.control_counts();
    int moved = 0;
    for (int k = 0; k < n.z; ++k)
      for (int j = 0; j < n.y; ++j)
        for (int i = 0; i < n.x; ++i) {
          const glm::dvec3 p = before.control_point(i, j, k);
          const double w = std::max(core::falloff_weight(f, glm::length(p - c0) / radius),
                                    core::falloff_weight(f, glm::length(p - c1) / radius));
          const glm::dvec3 expected = p - strength * w * core::column_direction(before, i, j);
          if (w == 0.0) {
            EXPECT_EQ(lattice().control_point(i, j, k), p) << name << " moved a point outside the sphere";
          } else {
            ++moved;
            EXPECT_LT(glm::length(lattice().control_point(i, j, k) - expected), 1e-15) << name;
            EXPECT_NEAR(core::column_direction(before, i, j).y, 1.0, 1e-12);  // ring columns are vertical
          }
        }
    EXPECT_GT(moved, 0) << name;
    EXPECT_LT(moved, n.x * n.y * n.z) << name;
    EXPECT_NE(scene.find("t")->world_mesh->positions, mesh_before) << name << ": the mesh did not follow";
    history.undo();  // restores the lattice and the mesh exactly
    EXPECT_EQ(lattice().control_points(), before.control_points()) << name;
    EXPECT_EQ(scene.find("t")->world_mesh->positions, mesh_before) << name;
  }
}

TEST_F(Pressing, PullColumnMovesTheWholeColumnAlongItsDirection) {
  const core::TrivariateBSpline<glm::dvec3> before = lattice();
  run(history, {{"cmd", "lattice.pull_column"}, {"object", "t"}, {"column", {5, 2}}, {"distance", 0.1}});
  const glm::ivec3 n = before.control_counts();
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::dvec3 p = before.control_point(i, j, k);
        if (i == 5 && j == 2)
          EXPECT_LT(glm::length(lattice().control_point(i, j, k) - (p + glm::dvec3(0.0, 0.1, 0.0))), 1e-12);
        else
          EXPECT_EQ(lattice().control_point(i, j, k), p);
      }
}

TEST_F(Pressing, BadParametersFailWithTheirFieldAndChangeNothing) {
  const std::vector<glm::dvec3> before = lattice().control_points();
  const auto expect_field = [&](const nlohmann::json& line, const std::string& field) {
    try {
      run(history, line);
      ADD_FAILURE() << "accepted " << line.dump();
    } catch (const core::CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    EXPECT_EQ(lattice().control_points(), before);
  };
  const nlohmann::json press = {{"cmd", "lattice.press"}, {"object", "t"},   {"path", {{0, 0, 0}}},
                                {"radius", 0.3},          {"strength", 0.1}, {"falloff", "smooth"}};
  nlohmann::json bad = press;
  bad["radius"] = -0.3;
  expect_field(bad, "radius");
  bad = press;
  bad["falloff"] = "wobbly";
  expect_field(bad, "falloff");
  bad = press;
  bad["path"] = nlohmann::json::array();
  expect_field(bad, "path");
  bad = press;
  bad["object"] = "nobody";
  expect_field(bad, "object");
  expect_field({{"cmd", "lattice.pull_column"}, {"object", "t"}, {"column", {16, 0}}, {"distance", 0.1}}, "column");
  run(history, {{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "plain"}});
  bad = press;
  bad["object"] = "plain";
  expect_field(bad, "object");  // no lattice
}

}  // namespace lattice_press_test
