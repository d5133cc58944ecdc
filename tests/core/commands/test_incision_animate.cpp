// incision.animate: the opening keyed through the morph channel incision.draw leaves — closed at 0 (input vertices at
// their input positions), as drawn at 1 (bit for bit), keyed in between; clear; undo; errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/commands/camera_set.h"
#include "core/commands/incision_animate.h"
#include "core/commands/incision_draw.h"
#include "core/commands/scene_primitive.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace incision_animate_test {

using nlohmann::json;
using test::run_line;
using test::throws_command_error;

Scene cut_sphere(TriMesh* before = nullptr) {
  Scene s;
  run_line<ScenePrimitiveCommand>(s, json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"));
  run_line<ScenePrimitiveCommand>(s, json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"plain"})"));
  run_line<CameraSetCommand>(s, json::parse(R"({"cmd":"camera.set","eye":[0,0,6],"target":[0,0,0],"fov_deg":45,
      "viewport":[800,600]})"));
  if (before) *before = *s.find("ball")->rest_mesh;
  run_line<IncisionDrawCommand>(s, json::parse(R"({"cmd":"incision.draw","object":"ball",
      "stroke":[[400,230],[400,265],[400,300],[400,335],[400,370]],"width":0.4,"depth":0.3,"opening":0.12})"));
  return s;
}

TEST(IncisionAnimate, TheChannelClosesAndOpensTheCut) {
  TriMesh sphere;
  Scene s = cut_sphere(&sphere);
  const SceneObject& cut = *s.find("ball");
  ASSERT_TRUE(cut.morph);
  EXPECT_FALSE(cut.morph->animated());
  EXPECT_EQ(cut.world_mesh->positions, cut.rest_mesh->positions);  // weight 1: as drawn, bit for bit
  const TriMesh closed = morphed(*cut.rest_mesh, *cut.morph, 0.0);
  std::size_t moved_by_cut = 0;
  for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
    EXPECT_LT(glm::length(closed.positions[v] - sphere.positions[v]), 1e-12) << v;  // closed: input positions
    moved_by_cut += cut.rest_mesh->positions[v] != sphere.positions[v];
  }
  EXPECT_GT(moved_by_cut, 0u);

  auto c = run_line<IncisionAnimateCommand>(s, json::parse(R"({"cmd":"incision.animate","object":"ball",
      "opening_keys":[[1,0],[25,1]]})"));
  const SceneObject& keyed = *s.find("ball");
  EXPECT_TRUE(keyed.animated());
  const Scene at0 = scene_at_time(s, 0.0), at1 = scene_at_time(s, 1.0), mid = scene_at_time(s, 0.5);
  EXPECT_EQ(at0.find("ball")->world_mesh->positions, closed.positions);
  EXPECT_EQ(at1.find("ball")->world_mesh->positions, cut.rest_mesh->positions);
  // Halfway in time, halfway open (linear keys), vertex by vertex.
  for (std::size_t v = 0; v < closed.positions.size(); v += 37) {
    const glm::dvec3 half = 0.5 * (closed.positions[v] + cut.rest_mesh->positions[v]);
    EXPECT_LT(glm::length(mid.find("ball")->world_mesh->positions[v] - half), 1e-12);
  }
  c->undo(s);
  EXPECT_FALSE(s.find("ball")->morph->animated());
  run_line<IncisionAnimateCommand>(
      s, json::parse(R"({"cmd":"incision.animate","object":"ball","opening_keys":[[3,0.5]]})"));
  EXPECT_FALSE(s.find("ball")->animated());
  EXPECT_NE(s.find("ball")->world_mesh->positions, cut.rest_mesh->positions);  // held half open
  run_line<IncisionAnimateCommand>(s, json::parse(R"({"cmd":"incision.animate","object":"ball","clear":true})"));
  EXPECT_EQ(s.find("ball")->world_mesh->positions, s.find("ball")->rest_mesh->positions);
}

TEST(IncisionAnimate, ErrorsNameTheirField) {
  Scene s = cut_sphere();
  const auto run = [&](const char* line) {
    return [&s, line] { run_line<IncisionAnimateCommand>(s, json::parse(line)); };
  };
  EXPECT_TRUE(throws_command_error(run(R"({"cmd":"incision.animate","object":"plain","opening_keys":[[1,0]]})"),
                                   "object", "no incision"));
  EXPECT_TRUE(throws_command_error(run(R"({"cmd":"incision.animate","object":"nope","opening_keys":[[1,0]]})"),
                                   "object", "nope"));
  EXPECT_TRUE(throws_command_error(run(R"({"cmd":"incision.animate","object":"ball"})"), "opening_keys", "key"));
  EXPECT_TRUE(throws_command_error(run(R"({"cmd":"incision.animate","object":"ball","opening_keys":[[2,0],[2,1]]})"),
                                   "opening_keys", "two keys"));
  EXPECT_TRUE(throws_command_error(
      run(R"({"cmd":"incision.animate","object":"ball","opening_keys":[[1,0],[9,-1e300]]})"), "opening_keys", "100"));
  // An animated opening refuses a new cut until cleared.
  run_line<IncisionAnimateCommand>(
      s, json::parse(R"({"cmd":"incision.animate","object":"ball","opening_keys":[[1,0],[9,1]]})"));
  EXPECT_TRUE(throws_command_error(
      [&] {
        run_line<IncisionDrawCommand>(s, json::parse(R"({"cmd":"incision.draw","object":"ball",
            "stroke":[[330,300],[470,300]],"width":0.4,"depth":0.3,"opening":0.1})"));
      },
      "object", "animated incision opening"));
}

}  // namespace incision_animate_test
}  // namespace trispline::core
