// object.transform (core/commands/object_transform.h): absolute location / rotation / scale, optional fields keep
// their value, the lattice (FFD, DFFD rig) moves with the object so its deformed shape moves rigidly, tile layers
// follow, undo restores bit for bit, bad values are refused with the field named and the scene untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/commands/camera_set.h"
#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_remove.h"
#include "core/commands/dffd_split.h"
#include "core/commands/object_transform.h"
#include "core/commands/place_sketch.h"
#include "core/commands/scene_primitive.h"
#include "core/scene/primitives.h"
#include "tests/core/commands/placed_crate.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace object_transform_test {

using nlohmann::json;

void run(Scene& s, const std::string& line) {
  trispline::test::run_line<ScenePrimitiveCommand, CameraSetCommand, PlaceSketchCommand, DffdSplitCommand,
                            DdmFillCommand, ObjectTransformCommand>(s, json::parse(line));
}

CommandPtr parse(const std::string& line) { return ObjectTransformCommand::parse(json::parse(line), {}); }

void expect_same_mesh(const TriMesh& a, const TriMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
}

// Every vertex of `after` is A·(the same vertex of `before`), A the change between the two transforms.
void expect_moved_rigidly(const SceneObject& before, const SceneObject& after, double tol) {
  const glm::dmat4 a = after.transform.matrix() * glm::inverse(before.transform.matrix());
  ASSERT_EQ(before.world_mesh->positions.size(), after.world_mesh->positions.size());
  double worst = 0;
  for (std::size_t v = 0; v < before.world_mesh->positions.size(); ++v) {
    const glm::dvec3 want(a * glm::dvec4(before.world_mesh->positions[v], 1.0));
    worst = std::max(worst, glm::length(want - after.world_mesh->positions[v]));
  }
  EXPECT_LT(worst, tol);
}

TEST(ObjectTransform, SetsAbsoluteValuesAndKeepsMissingFields) {
  Scene s;
  run(s, R"({"cmd":"scene.primitive","kind":"box","name":"b","translate":[1,2,3],"rotate_deg":[10,0,0],"scale":2})");
  const SceneObject before = *s.find("b");
  auto c = parse(R"({"cmd":"object.transform","object":"b","translate":[-1,0.5,4]})");
  EXPECT_EQ(c->to_json(), json::parse(R"({"cmd":"object.transform","object":"b","translate":[-1,0.5,4]})"));
  c->redo(s);
  const SceneObject& b = *s.find("b");
  EXPECT_EQ(b.transform.translate, glm::dvec3(-1, 0.5, 4));
  EXPECT_EQ(b.transform.rotate_deg, glm::dvec3(10, 0, 0));  // not given: kept
  EXPECT_EQ(b.transform.scale, glm::dvec3(2.0));
  expect_same_mesh(*b.world_mesh, transformed(*b.rest_mesh, b.transform));

  auto r = parse(R"({"cmd":"object.transform","object":"b","rotate_deg":[0,90,30],"scale":[1,2,3]})");
  r->redo(s);
  EXPECT_EQ(s.find("b")->transform.translate, glm::dvec3(-1, 0.5, 4));
  EXPECT_EQ(s.find("b")->transform.scale, glm::dvec3(1, 2, 3));
  expect_same_mesh(*s.find("b")->world_mesh, transformed(*before.rest_mesh, s.find("b")->transform));
  EXPECT_EQ(r->to_json()["scale"], json::parse("[1,2,3]"));

  r->undo(s);
  c->undo(s);
  const SceneObject& back = *s.find("b");
  EXPECT_EQ(back.world_mesh, before.world_mesh);  // the very same mesh: bit for bit
  EXPECT_EQ(back.transform.translate, before.transform.translate);
  EXPECT_EQ(back.transform.rotate_deg, before.transform.rotate_deg);
  EXPECT_EQ(back.transform.scale, before.transform.scale);
  c->redo(s);
  EXPECT_EQ(s.find("b")->transform.translate, glm::dvec3(-1, 0.5, 4));
}

TEST(ObjectTransform, MakeWritesEveryFieldAndUniformScaleAsANumber) {
  Transform t;
  t.translate = {1.5, 0, 0};
  t.scale = glm::dvec3(2.0);
  const json j = ObjectTransformCommand::make("o", t)->to_json();
  EXPECT_EQ(j, json::parse(R"({"cmd":"object.transform","object":"o","translate":[1.5,0,0],"rotate_deg":[0,0,0],
                               "scale":2})"));
}

struct BadCase {
  const char* line;
  const char* field;
  const char* words;
};

TEST(ObjectTransform, RefusesAbsurdValuesNamingTheFieldAndLeavesTheSceneAlone) {
  const BadCase cases[] = {
      {R"({"cmd":"object.transform","object":"b","translate":[2e9,0,0]})", "translate", "1e9"},
      {R"({"cmd":"object.transform","object":"b","translate":[0,"a",0]})", "translate", "number"},
      {R"({"cmd":"object.transform","object":"b","rotate_deg":[0,0,1e7]})", "rotate_deg", "1e6"},
      {R"({"cmd":"object.transform","object":"b","scale":0})", "scale", "non-zero"},
      {R"({"cmd":"object.transform","object":"b","scale":[1,-2,1]})", "scale", "(0, 1e6]"},
      {R"({"cmd":"object.transform","object":"b","scale":2e6})", "scale", "(0, 1e6]"},
      {R"({"cmd":"object.transform","translate":[0,0,0]})", "object", "object"},
  };
  for (const BadCase& c : cases)
    EXPECT_TRUE(trispline::test::throws_command_error([&] { parse(c.line); }, c.field, c.words)) << c.line;
  // NaN cannot be written in JSON text but can be in a json value built in code.
  json nan_line = {{"cmd", "object.transform"},
                   {"object", "b"},
                   {"translate", {0.0, std::numeric_limits<double>::quiet_NaN(), 0.0}}};
  EXPECT_THROW(ObjectTransformCommand::parse(nan_line, {}), CommandError);

  Scene s;
  run(s, R"({"cmd":"scene.primitive","kind":"box","name":"b"})");
  const auto mesh = s.find("b")->world_mesh;
  auto unknown = parse(R"({"cmd":"object.transform","object":"nobody","translate":[1,0,0]})");
  EXPECT_TRUE(trispline::test::throws_command_error([&] { unknown->redo(s); }, "object", "nobody"));
  EXPECT_EQ(s.find("b")->world_mesh, mesh);
  EXPECT_EQ(s.find("b")->transform.translate, glm::dvec3(0.0));
}

TEST(ObjectTransform, PlacedObjectMovesWithItsLattice) {
  Scene s = trispline::test::placed_crate();
  const SceneObject before = *s.find("crate");
  ASSERT_TRUE(before.ffd);
  ASSERT_TRUE(before.placement);
  auto c = parse(R"({"cmd":"object.transform","object":"crate","translate":[0.25,1,-0.5]})");
  c->redo(s);
  const SceneObject& moved = *s.find("crate");
  EXPECT_EQ(c->stats()["lattice_moved"], 1);
  // A translation moves every deformed vertex and control point by exactly the same vector (to rounding).
  expect_moved_rigidly(before, moved, 1e-12);
  const auto& p0 = before.ffd->lattice.control_points();
  const auto& p1 = moved.ffd->lattice.control_points();
  ASSERT_EQ(p0.size(), p1.size());
  for (std::size_t i = 0; i < p0.size(); ++i)
    EXPECT_LT(glm::length(p1[i] - (p0[i] + glm::dvec3(0.25, 1, -0.5))), 1e-12);
  EXPECT_EQ(moved.ffd->params, before.ffd->params);  // parameters kept, the embedding moved
  EXPECT_LT(
      glm::length(moved.placement->contact_points[0] - before.placement->contact_points[0] - glm::dvec3(0.25, 1, -0.5)),
      1e-12);
  // The moved embedding gives the moved rest mesh the same parameters.
  const auto params = embed_points(moved.ffd->embedding, moved.world_rest_mesh().positions);
  for (std::size_t v = 0; v < params.size(); ++v) ASSERT_LT(glm::length(params[v] - before.ffd->params[v]), 1e-9);

  // Rotation and (non-uniform) scale about the object's origin: still a rigid image of the deformed shape.
  auto r = parse(R"({"cmd":"object.transform","object":"crate","rotate_deg":[0,90,0],"scale":[1,2,1.5]})");
  const SceneObject mid = *s.find("crate");
  r->redo(s);
  expect_moved_rigidly(mid, *s.find("crate"), 1e-9);
  const SceneObject& turned = *s.find("crate");
  const auto again = embed_points(turned.ffd->embedding, turned.world_rest_mesh().positions);
  for (std::size_t v = 0; v < again.size(); ++v) ASSERT_LT(glm::length(again[v] - before.ffd->params[v]), 1e-9);

  r->undo(s);
  c->undo(s);
  EXPECT_EQ(s.find("crate")->world_mesh, before.world_mesh);
  EXPECT_EQ(s.find("crate")->ffd, before.ffd);
  EXPECT_EQ(s.find("crate")->placement, before.placement);
}

TEST(ObjectTransform, PreviewIsTheAffineImageOfTheCurrentEvaluation) {
  Scene s = trispline::test::placed_crate();
  const SceneObject& crate = *s.find("crate");
  Transform t = crate.transform;
  t.translate += glm::dvec3(1, 0, 0);
  t.rotate_deg.y = 30;
  const SceneObject preview = object_with_transform(crate, t, false);
  const SceneObject exact = object_with_transform(crate, t, true);
  ASSERT_EQ(preview.world_mesh->positions.size(), exact.world_mesh->positions.size());
  for (std::size_t v = 0; v < exact.world_mesh->positions.size(); ++v)
    ASSERT_LT(glm::length(preview.world_mesh->positions[v] - exact.world_mesh->positions[v]), 1e-9);
  EXPECT_EQ(preview.ffd->lattice.control_points(), exact.ffd->lattice.control_points());
}

TEST(ObjectTransform, MirroredLatticeObjectKeepsItsSigns) {
  Scene s = trispline::test::placed_crate(1.0, {-0.5, 0.2, 0.2});
  const auto mesh = s.find("crate")->world_mesh;
  auto c = parse(R"({"cmd":"object.transform","object":"crate","scale":1})");
  EXPECT_TRUE(trispline::test::throws_command_error([&] { c->redo(s); }, "scale", "mirror")) << "mirroring a lattice";
  EXPECT_EQ(s.find("crate")->world_mesh, mesh);
  // Moving it is fine; its negative scale is kept.
  parse(R"({"cmd":"object.transform","object":"crate","translate":[0,1,0]})")->redo(s);
  EXPECT_EQ(s.find("crate")->transform.scale.x, -0.5);
}

TEST(ObjectTransform, DffdRigMovesWithTheObject) {
  Scene s;
  run(s, R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","translate":[0,1,0],"scale":[1.2,0.6,0.6]})");
  run(s, R"({"cmd":"scene.primitive","kind":"cylinder","name":"bar","translate":[0.1,1.3,0.05],
             "scale":[0.15,0.9,0.15]})");
  run(s, R"({"cmd":"dffd.split","object":"ball","obstacles":["bar"],"axis":"x","w_axis":"y","order":[3,3,3],
             "controls":[16,12,12],"kernel":"gaussian","kernel_width":0.7,"openings":"open"})");
  const SceneObject before = *s.find("ball");
  ASSERT_TRUE(before.dffd);
  auto c = parse(R"({"cmd":"object.transform","object":"ball","translate":[3,1,0]})");
  c->redo(s);
  const SceneObject& moved = *s.find("ball");
  ASSERT_TRUE(moved.dffd);
  // The split depends only on parameters, so the evaluated mesh is the same one moved by the translation.
  const glm::dvec3 d = glm::dvec3(3, 1, 0) - before.transform.translate;
  ASSERT_EQ(moved.world_mesh->positions.size(), before.world_mesh->positions.size());
  double worst = 0;
  for (std::size_t v = 0; v < moved.world_mesh->positions.size(); ++v)
    worst = std::max(worst, glm::length(moved.world_mesh->positions[v] - before.world_mesh->positions[v] - d));
  EXPECT_LT(worst, 1e-9);
  c->undo(s);
  EXPECT_EQ(s.find("ball")->world_mesh, before.world_mesh);
  EXPECT_EQ(s.find("ball")->dffd, before.dffd);
}

TEST(ObjectTransform, TileLayersFollowInObjectSpace) {
  Scene s;
  s.insert(trispline::test::sphere_object("ball", 8, 4, {0, 0, 0}));
  run(s,
      R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"spikes","tile":"thorn","layout":"rect","counts":[1,1],
             "height":0.2})");
  const auto layer = s.find("ball")->ddm_layers.at(0);
  run(s, R"({"cmd":"object.transform","object":"ball","translate":[2,0,0],"scale":0.5})");
  const SceneObject& ball = *s.find("ball");
  ASSERT_EQ(ball.ddm_layers.size(), 1u);
  EXPECT_EQ(ball.ddm_layers[0], layer);  // the same layer: drawn and exported through the new transform
  EXPECT_EQ(ball.transform.scale, glm::dvec3(0.5));
}

}  // namespace object_transform_test
}  // namespace trispline::core
