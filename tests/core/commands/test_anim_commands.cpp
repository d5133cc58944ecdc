// Animation commands: anim.timeline, anim.keyframe, anim.clip, and the offset keys they drive
// (core::evaluate_offset_keys, core::scene_at_time). Commands run through parse + redo/undo on a real scene (a crate
// placed over a plane by place.sketch), as the editor's history runs them.
#include <gtest/gtest.h>

#include <cmath>

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_remove.h"
#include "core/commands/mesh_refine.h"
#include "core/scene/scene_export.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/commands/placed_crate.h"

namespace trispline::core {
namespace anim_commands_test {

using nlohmann::json;

using test::centroid;
using test::expect_same_meshes;
using test::place_line;
using test::placed_crate;

CommandPtr run(Scene& scene, const json& line) { return test::run_crate_line(scene, line); }

TEST(OffsetKeys, InterpolationModesAndHolds) {
  std::vector<OffsetKey> keys{{0.0, {0.0, 0, 0}, KeyInterpolation::linear},
                              {1.0, {1.0, 0, 0}, KeyInterpolation::smooth},
                              {2.0, {3.0, 0, 0}, KeyInterpolation::constant},
                              {3.0, {5.0, 0, 0}, KeyInterpolation::linear}};
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, -4.0).x, 0.0);    // held before the first key
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, 0.25).x, 0.25);   // linear
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, 1.5).x, 2.0);     // smooth: symmetric midpoint
  EXPECT_LT(evaluate_offset_keys(keys, 1.1).x, 1.1 * 2 - 1.0);  // eases out of the key (slower than linear)
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, 2.9).x, 3.0);     // constant holds
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, 3.0).x, 5.0);
  EXPECT_DOUBLE_EQ(evaluate_offset_keys(keys, 9.0).x, 5.0);  // held after the last key
  EXPECT_THROW(evaluate_offset_keys({}, 0.0), std::invalid_argument);
}

TEST(AnimTimeline, SetsUndoesAndRejectsBadRanges) {
  Scene s;
  auto c = run(s, json::parse(R"({"cmd":"anim.timeline","fps":30,"start":0,"end":59})"));
  EXPECT_EQ(s.timeline, (Timeline{30, 0, 59}));
  EXPECT_DOUBLE_EQ(s.timeline.time_of_frame(30), 1.0);
  c->undo(s);
  EXPECT_EQ(s.timeline, Timeline{});
  CommandContext ctx;
  EXPECT_THROW(AnimTimelineCommand::parse(json::parse(R"({"cmd":"anim.timeline","fps":0})"), ctx), CommandError);
  EXPECT_THROW(AnimTimelineCommand::parse(json::parse(R"({"cmd":"anim.timeline","fps":-24})"), ctx), CommandError);
  EXPECT_THROW(AnimTimelineCommand::parse(json::parse(R"({"cmd":"anim.timeline"})"), ctx), CommandError);
  auto bad = AnimTimelineCommand::parse(json::parse(R"({"cmd":"anim.timeline","start":50,"end":10})"), ctx);
  try {
    bad->redo(s);
    ADD_FAILURE() << "end < start accepted";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "end");
  }
  EXPECT_EQ(s.timeline, Timeline{});  // unchanged
}

TEST(AnimKeyframe, KeysMoveTheObjectAlongItsPathAndUndoExactly) {
  Scene s = placed_crate(0.5);
  const Scene before = s;
  run(s, json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":1,"u":0})"));
  auto second = run(s, json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":25,"u":0.5})"));
  const SceneObject& crate = *s.find("crate");
  ASSERT_EQ(crate.offset_keys.size(), 2u);
  EXPECT_DOUBLE_EQ(crate.offset_keys[1].time_s, 1.0);  // frame 25 at 24 fps from frame 1
  EXPECT_TRUE(crate.animated());
  // t = 0 is the first key: the mesh is unchanged by keying.
  EXPECT_EQ(crate.world_mesh->positions, before.find("crate")->world_mesh->positions);
  // Halfway the object has moved along the stroke (x grows along this stroke), at the end by more.
  const Scene mid = scene_at_time(s, 0.5), end = scene_at_time(s, 1.0);
  const double x0 = centroid(*crate.world_mesh).x, x1 = centroid(*mid.find("crate")->world_mesh).x,
               x2 = centroid(*end.find("crate")->world_mesh).x;
  EXPECT_GT(x1, x0 + 0.1);
  EXPECT_GT(x2, x1 + 0.1);
  EXPECT_FALSE(mid.find("crate")->animated());  // a still
  // Deterministic: the same time gives the same meshes bit for bit.
  expect_same_meshes(mid, scene_at_time(s, 0.5));
  second->undo(s);
  EXPECT_EQ(s.find("crate")->offset_keys.size(), 1u);
  EXPECT_FALSE(s.find("crate")->animated());
}

TEST(AnimKeyframe, RemoveAndErrorsLeaveTheSceneUnchanged) {
  Scene s = placed_crate();
  run(s, json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":10,"offset":[0.1,0,0]})"));
  const Scene keyed = s;
  CommandContext ctx;
  auto remove_missing = AnimKeyframeCommand::parse(
      json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":11,"remove":true})"), ctx);
  EXPECT_THROW(remove_missing->redo(s), CommandError);
  auto undeformed =
      AnimKeyframeCommand::parse(json::parse(R"({"cmd":"anim.keyframe","object":"ground","frame":1,"u":0})"), ctx);
  EXPECT_THROW(undeformed->redo(s), CommandError);
  EXPECT_THROW(AnimKeyframeCommand::parse(json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":1})"), ctx),
               CommandError);
  EXPECT_THROW(AnimKeyframeCommand::parse(
                   json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":1,"offset":[null,0,0]})"), ctx),
               CommandError);
  expect_same_meshes(s, keyed);
  EXPECT_EQ(s.find("crate")->offset_keys.size(), 1u);
  auto rm = run(s, json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":10,"remove":true})"));
  EXPECT_TRUE(s.find("crate")->offset_keys.empty());
  rm->undo(s);
  EXPECT_EQ(s.find("crate")->offset_keys.size(), 1u);
}

TEST(AnimClip, MissingFileIsAClearErrorAndChangesNothing) {
  Scene s = placed_crate();
  const Scene before = s;
  CommandContext ctx;
  auto c = AnimClipCommand::parse(
      json::parse(R"({"cmd":"anim.clip","object":"crate","path":"/nonexistent/walk.gltf"})"), ctx);
  EXPECT_TRUE(test::throws_command_error([&] { c->redo(s); }, "path", "walk.gltf")) << "missing clip file accepted";
  expect_same_meshes(s, before);
  EXPECT_EQ(s.find("crate")->clip, nullptr);
  EXPECT_THROW(
      AnimClipCommand::parse(json::parse(R"({"cmd":"anim.clip","object":"crate","path":"x.gltf","speed":0})"), ctx),
      CommandError);
}

}  // namespace anim_commands_test
}  // namespace trispline::core

#ifdef TRISPLINE_HAVE_CLIP_ASSETS
namespace trispline::core {
namespace anim_commands_test {

const std::string kData = std::string(TRISPLINE_SOURCE_DIR) + "/assets/data/";

// Two-level animation (seed §2.4.3): a glTF clip poses the flat rest mesh, the FFD of place.sketch warps each pose.
TEST(AnimClipReal, MorphCubeWalksAndMorphsUnderThePlacement) {
  Scene s;
  CommandContext ctx;
  run(s, json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":3})"));
  SceneLoadCommand::parse(json{{"cmd", "scene.load"},
                               {"path", kData + "AnimatedMorphCube/AnimatedMorphCube.gltf"},
                               {"name", "cube"},
                               {"scale", 4.0}},
                          ctx)
      ->redo(s);
  const Scene loaded = s;
  auto clip = AnimClipCommand::parse(
      json{{"cmd", "anim.clip"}, {"object", "cube"}, {"path", kData + "AnimatedMorphCube/AnimatedMorphCube.gltf"}},
      ctx);
  clip->redo(s);
  ASSERT_NE(s.find("cube")->clip, nullptr);
  const double duration = s.find("cube")->clip->clip->duration_s();
  ASSERT_GT(duration, 1.0);
  // Poses differ over the clip; the same time gives the same mesh bit for bit.
  const Scene a = scene_at_time(s, 0.25 * duration), b = scene_at_time(s, 0.5 * duration);
  EXPECT_NE(a.find("cube")->world_mesh->positions, b.find("cube")->world_mesh->positions);
  expect_same_meshes(a, scene_at_time(s, 0.25 * duration));
  // world_mesh is the pose at scene time 0.
  EXPECT_EQ(s.find("cube")->world_mesh->positions, scene_at_time(s, 0.0).find("cube")->world_mesh->positions);

  // Place it along a stroke: every pose of the clip lies inside the lattice's domain (embedding of all poses).
  run(s, json::parse(R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],"fov_deg":45,
                         "viewport":[800,600]})"));
  run(s, json::parse(R"({"cmd":"place.sketch","stroke":[[250,380],[400,330],[550,380]],"object":"cube",
                         "width":0.3,"height":0.3,"extent":0.5})"));
  const SceneObject& cube = *s.find("cube");
  ASSERT_TRUE(cube.ffd && cube.clip);
  for (int k = 0; k <= 8; ++k) {
    const Scene at_k = scene_at_time(s, duration * k / 8.0);
    const SceneObject& posed = *at_k.find("cube");
    for (const glm::dvec3& p : posed.ffd->params) {
      EXPECT_GE(p.x, -1e-9);
      EXPECT_LE(p.x, 0.5 + 1e-9);
      EXPECT_GE(p.z, -1e-9);
      EXPECT_LE(p.z, 1.0 + 1e-9);
    }
  }
  // mesh.refine refuses a clip object (it would break the clip's vertex correspondence) and changes nothing.
  const Scene placed = s;
  auto refine = MeshRefineCommand::parse(json::parse(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01})"), ctx);
  EXPECT_THROW(refine->redo(s), CommandError);
  expect_same_meshes(s, placed);
  // Removing the clip brings back the loaded (bind) pose under the same placement.
  run(s, json::parse(R"({"cmd":"anim.clip","object":"cube","remove":true})"));
  EXPECT_EQ(s.find("cube")->clip, nullptr);
  EXPECT_EQ(loaded.find("cube")->rest_mesh, s.find("cube")->rest_mesh);
}

// A tile layer laid before the clip rides on every pose (host triangles, core/scene/ddm_follow.h): it moves with the
// clip, stays finite, and the same time gives the same tiles bit for bit.
TEST(AnimClipReal, TilesRideOnTheClip) {
  Scene s;
  CommandContext ctx;
  SceneLoadCommand::parse(json{{"cmd", "scene.load"},
                               {"path", kData + "AnimatedMorphCube/AnimatedMorphCube.gltf"},
                               {"name", "cube"},
                               {"scale", 4.0}},
                          ctx)
      ->redo(s);
  DdmFillCommand::parse(
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"cube","layer":"t","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.05})"),
      ctx)
      ->redo(s);
  AnimClipCommand::parse(
      json{{"cmd", "anim.clip"}, {"object", "cube"}, {"path", kData + "AnimatedMorphCube/AnimatedMorphCube.gltf"}}, ctx)
      ->redo(s);
  const double duration = s.find("cube")->clip->clip->duration_s();
  const auto tiles = [&](double t) {
    const SceneExport ex = scene_export_nodes(scene_at_time(s, t));
    EXPECT_EQ(ex.nodes.size(), 2u);
    return ex.nodes.back().mesh->positions;
  };
  const std::vector<glm::dvec3> a = tiles(0.25 * duration), b = tiles(0.5 * duration);
  EXPECT_NE(a, b);
  EXPECT_EQ(a, tiles(0.25 * duration));
  for (const glm::dvec3& p : b) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
}

TEST(AnimClipReal, VertexCountMismatchIsRejected) {
  Scene s = placed_crate();
  const Scene before = s;
  CommandContext ctx;
  auto c = AnimClipCommand::parse(
      json{{"cmd", "anim.clip"}, {"object", "crate"}, {"path", kData + "simple_skin/simple_skin.gltf"}}, ctx);
  EXPECT_TRUE(test::throws_command_error([&] { c->redo(s); }, "path", "vertices"))
      << "a clip with another vertex count was attached";
  expect_same_meshes(s, before);
}

}  // namespace anim_commands_test
}  // namespace trispline::core
#endif
