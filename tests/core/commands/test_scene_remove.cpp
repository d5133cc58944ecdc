// scene.remove (core/commands/scene_remove.h): the named object goes, the others keep their order, undo puts it back
// at its place bit for bit (a deformed one with its lattice), an unknown name is refused with the scene untouched.
#include <gtest/gtest.h>

#include "core/commands/scene_remove.h"
#include "tests/core/commands/placed_crate.h"

namespace trispline::core {
namespace scene_remove_test {

using nlohmann::json;

CommandPtr parse(const std::string& line) { return SceneRemoveCommand::parse(json::parse(line), {}); }

TEST(SceneRemove, RemovesTheObjectAndUndoPutsItBackInPlace) {
  Scene s = test::placed_crate();
  test::run_crate_line(s, json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","scale":0.3})"));
  const Scene before = s;
  const SceneObject crate = *s.find("crate");
  ASSERT_TRUE(crate.ffd);
  auto c = parse(R"({"cmd":"scene.remove","name":"crate"})");
  EXPECT_EQ(c->to_json(), json::parse(R"({"cmd":"scene.remove","name":"crate"})"));
  c->redo(s);
  ASSERT_EQ(s.objects().size(), 2u);
  EXPECT_EQ(s.find("crate"), nullptr);
  EXPECT_EQ(s.objects()[0].name, "ground");
  EXPECT_EQ(s.objects()[1].name, "ball");
  c->undo(s);
  test::expect_same_meshes(s, before);  // back between ground and ball
  EXPECT_EQ(s.find("crate")->ffd, crate.ffd);
  EXPECT_EQ(s.find("crate")->rest_mesh, crate.rest_mesh);
  c->redo(s);
  EXPECT_EQ(s.find("crate"), nullptr);
  EXPECT_EQ(s.objects().size(), 2u);
}

TEST(SceneRemove, UnknownOrMissingNameIsRefusedAndTheSceneIsUntouched) {
  Scene s = test::placed_crate();
  const Scene before = s;
  EXPECT_TRUE(test::throws_command_error([&] { parse(R"({"cmd":"scene.remove","name":"nobody"})")->redo(s); }, "name",
                                         "no object named 'nobody'"));
  EXPECT_EQ(test::command_field_of<SceneRemoveCommand>(s, json::parse(R"({"cmd":"scene.remove"})")), "name");
  EXPECT_EQ(test::command_field_of<SceneRemoveCommand>(s, json::parse(R"({"cmd":"scene.remove","name":3})")), "name");
  test::expect_same_meshes(s, before);
}

}  // namespace scene_remove_test
}  // namespace trispline::core
