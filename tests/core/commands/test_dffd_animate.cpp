// dffd.animate (core/commands/dffd_animate.h): a split's seam keyed between its capped openings (s = 0) and its
// stitched seam (s = 1) — each end bit for bit the split dffd.split builds with that openings value, a straight line
// per vertex in between, composed with the walk; clear; undo; a moved object keeps both seam states; errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/dffd_animate.h"
#include "core/commands/dffd_split.h"
#include "core/commands/object_transform.h"
#include "core/commands/scene_primitive.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace dffd_animate_test {

using nlohmann::json;
using test::run_line;
using test::throws_command_error;

// A sphere split around a cylinder that stands through it (the seam opens round the cylinder's cross-section).
Scene split_ball(const char* openings) {
  Scene s;
  run_line<ScenePrimitiveCommand>(s, json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"));
  run_line<ScenePrimitiveCommand>(s, json::parse(R"({"cmd":"scene.primitive","kind":"cylinder","name":"tool",
      "scale":[0.3,1.6,0.3],"translate":[0.013,0,0.017]})"));
  json split = json::parse(R"({"cmd":"dffd.split","object":"ball","obstacles":["tool"],"axis":"x","w_axis":"y",
      "order":[3,3,3],"controls":[16,12,12],"kernel":"gaussian","kernel_width":0.7})");
  split["openings"] = openings;
  run_line<DffdSplitCommand>(s, split);
  return s;
}

const TriMesh& mesh_of(const Scene& s) { return *s.find("ball")->world_mesh; }

TEST(DffdAnimate, TheSeamMovesFromCappedToStitched) {
  Scene s = split_ball("cap");
  const Scene capped = s, stitched = split_ball("stitch");
  ASSERT_TRUE(s.find("ball")->dffd->seam);
  ASSERT_EQ(mesh_of(capped).triangles, mesh_of(stitched).triangles);  // one topology: the caps do not depend on s
  std::size_t moved = 0;
  for (std::size_t v = 0; v < mesh_of(capped).positions.size(); ++v)
    moved += glm::length(mesh_of(capped).positions[v] - mesh_of(stitched).positions[v]) > 1e-6;
  EXPECT_GT(moved, 20u) << "stitching moves the vertices of the opened rows";

  auto c = run_line<DffdAnimateCommand>(s, json::parse(R"({"cmd":"dffd.animate","object":"ball",
      "stitch_keys":[[1,0],[25,1]]})"));
  EXPECT_TRUE(s.find("ball")->dffd_animated());
  EXPECT_EQ(c->stats().at("keys"), 2);
  EXPECT_EQ(c->stats().at("stitch_at_start"), 0.0);
  const Scene at0 = scene_at_time(s, 0.0), at1 = scene_at_time(s, 1.0), mid = scene_at_time(s, 0.5);
  EXPECT_EQ(mesh_of(at0).positions, mesh_of(capped).positions);    // s = 0: the capped split, bit for bit
  EXPECT_EQ(mesh_of(at1).positions, mesh_of(stitched).positions);  // s = 1: the stitched split, bit for bit
  EXPECT_EQ(mesh_of(s).positions, mesh_of(at0).positions);         // world_mesh is scene time 0
  ASSERT_EQ(mesh_of(mid).positions.size(), mesh_of(capped).positions.size());
  double worst = 0.0;  // halfway in time, halfway between the two states, vertex by vertex
  for (std::size_t v = 0; v < mesh_of(mid).positions.size(); ++v) {
    const glm::dvec3 half = 0.5 * (mesh_of(capped).positions[v] + mesh_of(stitched).positions[v]);
    worst = std::max(worst, glm::length(mesh_of(mid).positions[v] - half));
  }
  EXPECT_LT(worst, 1e-12);

  c->undo(s);
  EXPECT_TRUE(s.find("ball")->dffd->stitch_keys.empty());
  EXPECT_EQ(mesh_of(s).positions, mesh_of(capped).positions);
  c->redo(s);
  EXPECT_EQ(mesh_of(scene_at_time(s, 1.0)).positions, mesh_of(stitched).positions);  // redo: the same, bit for bit
  run_line<DffdAnimateCommand>(s, json::parse(R"({"cmd":"dffd.animate","object":"ball","clear":true})"));
  EXPECT_FALSE(s.find("ball")->dffd_animated());
  EXPECT_EQ(mesh_of(scene_at_time(s, 1.0)).positions, mesh_of(capped).positions);  // as dffd.split built it
}

TEST(DffdAnimate, AStitchedSplitOpensAndOneKeyHolds) {
  Scene s = split_ball("stitch");
  const Scene capped = split_ball("cap");
  run_line<DffdAnimateCommand>(s, json::parse(R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[5,0]]})"));
  EXPECT_FALSE(s.find("ball")->animated());  // one key holds its state at every time
  EXPECT_EQ(mesh_of(s).positions, mesh_of(capped).positions);
  EXPECT_EQ(mesh_of(scene_at_time(s, 3.0)).positions, mesh_of(capped).positions);
}

TEST(DffdAnimate, ComposesWithTheWalk) {
  Scene s = split_ball("cap");
  run_line<AnimKeyframeCommand>(
      s, json::parse(R"({"cmd":"anim.keyframe","object":"ball","frame":1,"offset":[-0.3,0,0]})"));
  run_line<AnimKeyframeCommand>(
      s, json::parse(R"({"cmd":"anim.keyframe","object":"ball","frame":25,"offset":[0.3,0,0]})"));
  const Scene walk_only = s;
  run_line<DffdAnimateCommand>(s, json::parse(R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[1,0],[25,1]],
      "interpolation":"smooth"})"));
  for (const double t : {0.0, 0.25, 0.5, 1.0}) {
    const Scene keyed_at = scene_at_time(s, t), walk_at = scene_at_time(walk_only, t);
    const TriMesh& keyed = mesh_of(keyed_at);
    const TriMesh& walk = mesh_of(walk_at);
    ASSERT_EQ(keyed.triangles, walk.triangles) << t;  // the split follows the offset only
    const double weight = s.find("ball")->dffd->stitch_keys.empty() ? -1.0 : dffd_stitch_at(*s.find("ball")->dffd, t);
    if (t == 0.0) {
      EXPECT_EQ(keyed.positions, walk.positions);  // s = 0 at the first key
    } else {
      EXPECT_GT(weight, 0.0);
    }
  }
  // The same times twice give the same meshes, bit for bit (determinism).
  EXPECT_EQ(mesh_of(scene_at_time(s, 0.5)).positions, mesh_of(scene_at_time(s, 0.5)).positions);
}

TEST(DffdAnimate, AMovedObjectKeepsBothSeamStates) {
  Scene s = split_ball("cap");
  run_line<DffdAnimateCommand>(s,
                               json::parse(R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[1,0],[25,1]]})"));
  const TriMesh before = mesh_of(scene_at_time(s, 1.0));
  run_line<ObjectTransformCommand>(s, json::parse(R"({"cmd":"object.transform","object":"ball","translate":[0,0,2]})"));
  const TriMesh after = mesh_of(scene_at_time(s, 1.0));
  ASSERT_EQ(before.positions.size(), after.positions.size());
  for (std::size_t v = 0; v < before.positions.size(); ++v)
    ASSERT_LT(glm::length(after.positions[v] - (before.positions[v] + glm::dvec3(0, 0, 2))), 1e-9) << v;
}

TEST(DffdAnimate, ErrorsNameTheirFieldAndChangeNothing) {
  Scene s = split_ball("cap");
  Scene open = split_ball("open");
  const Scene before = s;
  const auto run = [](Scene& scene, const char* line) {
    return [&scene, line] { run_line<DffdAnimateCommand>(scene, json::parse(line)); };
  };
  EXPECT_TRUE(throws_command_error(run(open, R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[1,0]]})"),
                                   "object", "open"));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"tool","stitch_keys":[[1,0]]})"), "object",
                                   "not split"));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"nope","stitch_keys":[[1,0]]})"), "object",
                                   "nope"));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"ball"})"), "stitch_keys", "key"));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[2,0],[2,1]]})"),
                                   "stitch_keys", "two keys"));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[2,0],[3]]})"),
                                   "stitch_keys", ""));
  EXPECT_TRUE(throws_command_error(run(s, R"({"cmd":"dffd.animate","object":"ball","stitch_keys":[[1,0],[9,1e300]]})"),
                                   "stitch_keys", "100"));
  test::expect_same_meshes(s, before);
  EXPECT_TRUE(s.find("ball")->dffd->stitch_keys.empty());
}

}  // namespace dffd_animate_test
}  // namespace trispline::core
