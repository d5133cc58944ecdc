// scene.primitive (core/commands/scene_primitive.h): every kind adds the generated mesh under its transform, a missing
// name is made unique and logged, undo removes the object bit for bit, bad fields are named and change nothing.
#include <gtest/gtest.h>

#include "core/commands/scene_primitive.h"
#include "core/scene/primitives.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace scene_primitive_test {

using nlohmann::json;

CommandPtr parse(const std::string& line) { return ScenePrimitiveCommand::parse(json::parse(line), {}); }

TEST(ScenePrimitive, EveryKindAddsItsGeneratedMeshUnderTheTransform) {
  for (const char* kind : {"teapot", "plane", "sphere", "box", "cylinder", "terrain"}) {
    Scene s;
    auto c = parse(std::string(R"({"cmd":"scene.primitive","kind":")") + kind +
                   R"(","name":"p","translate":[1,2,3],"rotate_deg":[0,90,0],"scale":2,"seed":7})");
    c->redo(s);
    ASSERT_EQ(s.objects().size(), 1u) << kind;
    const SceneObject& o = *s.find("p");
    EXPECT_EQ(o.source, std::string("primitive:") + kind);
    const TriMesh want = make_primitive(parse_primitive_kind(kind), 7);
    EXPECT_EQ(o.rest_mesh->positions, want.positions) << kind;
    EXPECT_EQ(o.rest_mesh->triangles, want.triangles) << kind;
    EXPECT_EQ(o.transform.translate, glm::dvec3(1, 2, 3));
    EXPECT_EQ(o.transform.rotate_deg, glm::dvec3(0, 90, 0));
    EXPECT_EQ(o.transform.scale, glm::dvec3(2.0));
    EXPECT_EQ(o.world_mesh->positions, transformed(want, o.transform).positions) << kind;
    EXPECT_EQ(c->stats().at("triangles"), want.triangle_count());
  }
}

TEST(ScenePrimitive, MissingNamesAreMadeUniqueAndLogged) {
  Scene s;
  auto a = parse(R"({"cmd":"scene.primitive","kind":"sphere"})");
  auto b = parse(R"({"cmd":"scene.primitive","kind":"sphere"})");
  a->redo(s);
  b->redo(s);
  ASSERT_EQ(s.objects().size(), 2u);
  EXPECT_EQ(s.objects()[0].name, "sphere");
  EXPECT_EQ(s.objects()[1].name, "sphere.001");
  EXPECT_EQ(b->to_json().at("name"), "sphere.001");  // the logged line replays to the same name
  EXPECT_EQ(parse(b->to_json().dump())->to_json(), b->to_json());
}

TEST(ScenePrimitive, RedoThenUndoLeavesTheSceneAsBefore) {
  Scene s;
  parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":3})")->redo(s);
  const Scene before = s;
  auto c = parse(R"({"cmd":"scene.primitive","kind":"terrain","name":"hills","seed":3,"color":[0.2,0.4,0.6]})");
  c->redo(s);
  ASSERT_EQ(s.objects().size(), 2u);
  const std::vector<glm::dvec3> added = s.find("hills")->world_mesh->positions;
  EXPECT_EQ(s.find("hills")->color, glm::vec3(glm::dvec3(0.2, 0.4, 0.6)));
  c->undo(s);
  trispline::test::expect_same_meshes(s, before);
  EXPECT_EQ(s.find("hills"), nullptr);
  c->redo(s);
  EXPECT_EQ(s.find("hills")->world_mesh->positions, added) << "redo is deterministic";
}

TEST(ScenePrimitive, BadFieldsAreNamedAndTheSceneIsUntouched) {
  Scene s;
  parse(R"({"cmd":"scene.primitive","kind":"box","name":"b"})")->redo(s);
  const Scene before = s;
  const auto field_of = [&](const char* line) {
    return trispline::test::command_field_of<ScenePrimitiveCommand>(s, json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive","kind":"torus"})"), "kind");
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive"})"), "kind");
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive","kind":"box","scale":0})"), "scale");
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive","kind":"box","translate":[1,2]})"), "translate");
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive","kind":"box","color":[0.5,1.5,0]})"), "color");
  EXPECT_EQ(field_of(R"({"cmd":"scene.primitive","kind":"box","name":"b"})"), "name");  // taken
  EXPECT_TRUE(trispline::test::throws_command_error(
      [&] { parse(R"({"cmd":"scene.primitive","kind":"box","name":"b"})")->redo(s); }, "name", "already exists"));
  EXPECT_TRUE(trispline::test::throws_command_error([&] { parse(R"({"cmd":"scene.primitive","kind":"torus"})"); },
                                                    "kind", "field 'kind'"));
  trispline::test::expect_same_meshes(s, before);
}

}  // namespace scene_primitive_test
}  // namespace trispline::core
