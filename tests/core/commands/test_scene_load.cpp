// scene.load (core/commands/scene_load.h): a mesh file becomes an object named after its stem, a relative path is
// resolved against the log's folder and logged absolute, loose points and lines are refused unless ignored, undo
// removes the object bit for bit, a file that does not load is blamed on "path" and changes nothing.
#include <gtest/gtest.h>

#include "core/commands/scene_load.h"
#include "core/mesh/mesh_io.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/mesh/mesh_test_util.h"

namespace trispline::core {
namespace scene_load_test {

using nlohmann::json;
using test::TempDir;
using test::write_text;

const char* kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";

CommandPtr parse(const json& line, const std::filesystem::path& base_dir = {}) {
  return SceneLoadCommand::parse(line, CommandContext{base_dir, {}});
}

TEST(SceneLoad, AddsTheFileUnderItsStemAndUndoRemovesIt) {
  TempDir dir;
  write_text(dir / "quad.obj", kQuad);
  Scene s;
  auto c = parse(json{{"cmd", "scene.load"}, {"path", "quad.obj"}, {"translate", {0, 1, 0}}, {"scale", 2}}, dir.path());
  // The logged line holds the absolute path, so the session log replays from any folder.
  EXPECT_EQ(c->to_json().at("path"), (dir / "quad.obj").string());
  c->redo(s);
  ASSERT_EQ(s.objects().size(), 1u);
  const SceneObject& o = *s.find("quad");
  const TriMesh file = load_mesh(dir / "quad.obj");
  EXPECT_EQ(o.rest_mesh->positions, file.positions);
  EXPECT_EQ(o.rest_mesh->triangles, file.triangles);
  EXPECT_EQ(o.world_mesh->positions, transformed(file, o.transform).positions);
  EXPECT_EQ(o.source, (dir / "quad.obj").string());
  EXPECT_EQ(c->stats().at("triangles"), 2);
  EXPECT_EQ(c->to_json().at("name"), "quad");
  // A second load of the same file gets a unique name; undo removes it and leaves the first bit for bit.
  const Scene before = s;
  auto again = parse(json{{"cmd", "scene.load"}, {"path", (dir / "quad.obj").string()}});
  again->redo(s);
  EXPECT_EQ(s.objects()[1].name, "quad.001");
  again->undo(s);
  trispline::test::expect_same_meshes(s, before);
  again->redo(s);
  EXPECT_EQ(s.find("quad.001")->world_mesh->positions, s.find("quad")->rest_mesh->positions);
}

TEST(SceneLoad, LooseGeometryIsRefusedUnlessIgnored) {
  TempDir dir;
  write_text(dir / "mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nl 1 4\np 4\n");
  Scene s;
  const json line = {{"cmd", "scene.load"}, {"path", (dir / "mixed.obj").string()}};
  EXPECT_TRUE(trispline::test::throws_command_error([&] { parse(line)->redo(s); }, "path", "1 point and 1 line"));
  EXPECT_TRUE(s.objects().empty());
  json ignore = line;
  ignore["loose"] = "ignore";
  auto c = parse(ignore);
  c->redo(s);
  EXPECT_EQ(s.find("mixed")->rest_mesh->triangle_count(), 1u);
  EXPECT_EQ(c->stats().at("ignored_points"), 1);
  EXPECT_EQ(c->stats().at("ignored_lines"), 1);
  EXPECT_EQ(c->to_json().at("loose"), "ignore");
  EXPECT_EQ(parse(line)->to_json().count("loose"), 0u);  // the default is not written
}

TEST(SceneLoad, BadFieldsAreNamedAndTheSceneIsUntouched) {
  TempDir dir;
  write_text(dir / "quad.obj", kQuad);
  write_text(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 1 1\nf 1 2 3\n");
  Scene s;
  parse(json{{"cmd", "scene.load"}, {"path", (dir / "quad.obj").string()}})->redo(s);
  const Scene before = s;
  const auto field_of = [&](const json& line) { return trispline::test::command_field_of<SceneLoadCommand>(s, line); };
  EXPECT_EQ(field_of({{"cmd", "scene.load"}, {"path", (dir / "missing.obj").string()}}), "path");
  EXPECT_EQ(field_of({{"cmd", "scene.load"}, {"path", (dir / "broken.obj").string()}}), "path");
  EXPECT_EQ(field_of({{"cmd", "scene.load"}}), "path");
  EXPECT_EQ(field_of({{"cmd", "scene.load"}, {"path", (dir / "quad.obj").string()}, {"name", "quad"}}), "name");
  EXPECT_EQ(field_of({{"cmd", "scene.load"}, {"path", (dir / "quad.obj").string()}, {"loose", "keep"}}), "loose");
  EXPECT_EQ(field_of({{"cmd", "scene.load"}, {"path", (dir / "quad.obj").string()}, {"scale", {1, 0, 1}}}), "scale");
  EXPECT_TRUE(trispline::test::throws_command_error(
      [&] {
        parse({{"cmd", "scene.load"}, {"path", (dir / "broken.obj").string()}})->redo(s);
      },
      "path", "a vertex needs 3 coordinates"));
  trispline::test::expect_same_meshes(s, before);
}

}  // namespace scene_load_test
}  // namespace trispline::core
