// lattice.animate_offset (core/commands/lattice_animate_offset.h) on a teapot on a ring lattice (lattice.ring): the
// lattice is periodic along u, so moving the object by a whole period (or by the ring's symmetry) is exact; undo
// restores the still object bit for bit; bad fields are named and change nothing.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/commands/lattice_animate_offset.h"
#include "core/commands/lattice_ring.h"
#include "core/commands/scene_primitive.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace lattice_animate_offset_test {

using nlohmann::json;

CommandPtr run(Scene& s, const json& line) {
  return test::run_line<ScenePrimitiveCommand, LatticeRingCommand, LatticeAnimateOffsetCommand>(s, line);
}

// A teapot ("t") on a 16-point ring lattice around (0.5, 0.1, -0.25), radius 1.2.
Scene ring_teapot() {
  Scene s;
  run(s, {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}});
  run(s, {{"cmd", "lattice.ring"}, {"object", "t"}, {"center", {0.5, 0.1, -0.25}}, {"radius", 1.2}});
  return s;
}

double max_distance(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
  return d;
}

TEST(LatticeAnimateOffset, OneFullPeriodReturnsToTheStartAndAQuarterTurnIsARotation) {
  Scene scene = ring_teapot();
  auto c = run(scene, {{"cmd", "lattice.animate_offset"}, {"object", "t"}, {"velocity", {0.25, 0.0, 0.0}}});
  const std::vector<glm::dvec3> start = scene.find("t")->world_mesh->positions;
  const Scene full_turn = scene_at_time(scene, 4.0);  // offset 1 = one period
  EXPECT_LT(max_distance(full_turn.find("t")->world_mesh->positions, start), 1e-9);
  // 16 control points on a circle: an offset of 4/16 moves the control net onto itself turned by 90° about the
  // ring's axis (θ from +x towards +z), so the deformed object turns exactly, up to rounding.
  const Scene quarter = scene_at_time(scene, 1.0);
  std::vector<glm::dvec3> turned;
  for (const auto& p : start) turned.emplace_back(0.5 - (p.z + 0.25), p.y, -0.25 + (p.x - 0.5));
  EXPECT_LT(max_distance(quarter.find("t")->world_mesh->positions, turned), 1e-9);
  EXPECT_GT(max_distance(quarter.find("t")->world_mesh->positions, start), 0.5);  // it did move
  // The scene itself is untouched by scene_at_time, and undo restores the still object bit for bit.
  EXPECT_EQ(scene.find("t")->world_mesh->positions, start);
  c->undo(scene);
  EXPECT_EQ(scene.find("t")->offset_velocity, glm::dvec3(0.0));
  EXPECT_EQ(scene.find("t")->world_mesh->positions, start);
}

TEST(LatticeAnimateOffset, OffsetShowsTheShiftedPoseAndUndoRestoresBitForBit) {
  Scene s = ring_teapot();
  const Scene before = s;
  const json line =
      json::parse(R"({"cmd":"lattice.animate_offset","object":"t","offset":[0.25,0,0],"velocity":[0,0,0]})");
  auto c = run(s, line);
  EXPECT_EQ(c->to_json(), line);
  EXPECT_EQ(s.find("t")->param_offset, glm::dvec3(0.25, 0, 0));
  EXPECT_EQ(c->stats().at("vertices"), s.find("t")->world_mesh->positions.size());
  EXPECT_GT(max_distance(s.find("t")->world_mesh->positions, before.find("t")->world_mesh->positions), 0.5);
  c->undo(s);
  test::expect_same_meshes(s, before);
  EXPECT_EQ(s.find("t")->param_offset, glm::dvec3(0.0));
  // A whole period of offset is the start pose, up to rounding.
  run(s, json::parse(R"({"cmd":"lattice.animate_offset","object":"t","offset":[1,0,0]})"));
  EXPECT_LT(max_distance(s.find("t")->world_mesh->positions, before.find("t")->world_mesh->positions), 1e-9);
}

TEST(LatticeAnimateOffset, BadFieldsAreNamedAndTheSceneIsUntouched) {
  Scene s = ring_teapot();
  run(s, {{"cmd", "scene.primitive"}, {"kind", "box"}, {"name", "plain"}});
  const Scene before = s;
  const auto field_of = [&](const char* line) {
    return test::command_field_of<LatticeAnimateOffsetCommand>(s, json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"nobody","velocity":[1,0,0]})"), "object");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"plain","velocity":[1,0,0]})"), "object");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","velocity":[1,0,0]})"), "object");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"t","velocity":[101,0,0]})"), "velocity");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"t","velocity":[1,0]})"), "velocity");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"t","offset":[0,"a",0]})"), "offset");
  EXPECT_EQ(field_of(R"({"cmd":"lattice.animate_offset","object":"t","offset":[0,2e6,0]})"), "offset");
  test::expect_same_meshes(s, before);
  EXPECT_EQ(s.find("t")->offset_velocity, glm::dvec3(0.0));
}

}  // namespace lattice_animate_offset_test
}  // namespace trispline::core
