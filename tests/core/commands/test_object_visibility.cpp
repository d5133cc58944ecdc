// object.visibility (core/commands/object_visibility.h): the viewport and render flags of an object and of a volume,
// each alone or both; undo restores what was there; an unknown name or a line without either flag is refused with
// the scene untouched. What the flags mean for outputs: scene_export_nodes and render_visible_scene (scene_export.h)
// hold render-visible objects only, Scene::bounds viewport-visible ones only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "core/commands/object_visibility.h"
#include "core/commands/scene_primitive.h"
#include "core/commands/volume_load.h"
#include "core/scene/scene_export.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace object_visibility_test {

using nlohmann::json;

CommandPtr parse(const std::string& line) { return ObjectVisibilityCommand::parse(json::parse(line), {}); }

// A unit sphere "ball" at the origin and a box "far" 100 units away along x.
Scene two_objects() {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"), {})->redo(s);
  ScenePrimitiveCommand::parse(
      json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"far","translate":[100,0,0]})"), {})
      ->redo(s);
  return s;
}

std::vector<std::string> node_names(const Scene& s) {
  std::vector<std::string> out;
  for (const GltfNode& n : scene_export_nodes(s).nodes) out.push_back(n.name);
  return out;
}

TEST(ObjectVisibility, ViewportFlagHidesFromBoundsAndUndoShowsAgain) {
  Scene s = two_objects();
  ASSERT_GT(s.bounds().hi.x, 90.0);
  auto c = parse(R"({"cmd":"object.visibility","object":"far","viewport":false})");
  EXPECT_EQ(c->to_json(), json::parse(R"({"cmd":"object.visibility","object":"far","viewport":false})"));
  EXPECT_EQ(c->label(), "Hide 'far'");
  c->redo(s);
  EXPECT_FALSE(s.find("far")->visible);
  EXPECT_TRUE(s.find("far")->render_visible) << "the render flag is not given: unchanged";
  EXPECT_LT(s.bounds().hi.x, 2.0) << "Home frames viewport-visible objects only";
  EXPECT_EQ(node_names(s), (std::vector<std::string>{"ball", "far"})) << "hidden in the viewport, still exported";
  c->undo(s);
  EXPECT_TRUE(s.find("far")->visible);
  EXPECT_GT(s.bounds().hi.x, 90.0);
  c->redo(s);
  EXPECT_FALSE(s.find("far")->visible);
}

TEST(ObjectVisibility, RenderFlagLeavesExportsAndRenderScene) {
  Scene s = two_objects();
  auto hide_render = parse(R"({"cmd":"object.visibility","object":"ball","render":false})");
  EXPECT_EQ(hide_render->label(), "Do not render 'ball'");
  hide_render->redo(s);
  EXPECT_TRUE(s.find("ball")->visible);
  EXPECT_FALSE(s.find("ball")->render_visible);
  EXPECT_EQ(node_names(s), std::vector<std::string>{"far"});
  // Viewport-hidden but render-visible: renders show it (hide_render decides, as in Blender).
  parse(R"({"cmd":"object.visibility","object":"far","viewport":false})")->redo(s);
  const Scene r = render_visible_scene(s);
  ASSERT_EQ(r.objects().size(), 1u);
  EXPECT_EQ(r.objects()[0].name, "far");
  EXPECT_TRUE(r.objects()[0].visible);
  EXPECT_EQ(r.objects()[0].world_mesh, s.find("far")->world_mesh) << "meshes are shared, not copied";
  hide_render->undo(s);
  EXPECT_TRUE(s.find("ball")->render_visible);
  EXPECT_EQ(node_names(s), (std::vector<std::string>{"ball", "far"}));
}

TEST(ObjectVisibility, BothFlagsOnAVolume) {
  Scene s;
  VolumeLoadCommand::parse(json::parse(R"({"cmd":"volume.load","analytic":"sphere","name":"vol"})"), {})->redo(s);
  ASSERT_TRUE(s.bounds().valid());
  auto c = parse(R"({"cmd":"object.visibility","object":"vol","viewport":false,"render":false})");
  EXPECT_EQ(c->label(), "Hide, Do not render 'vol'");
  const auto spline = s.volumes()[0].spline;
  c->redo(s);
  EXPECT_FALSE(s.find_volume("vol")->visible);
  EXPECT_FALSE(s.find_volume("vol")->render_visible);
  EXPECT_EQ(s.find_volume("vol")->spline, spline) << "the spline is shared, not rebuilt";
  EXPECT_FALSE(s.bounds().valid()) << "nothing viewport-visible";
  EXPECT_TRUE(render_visible_scene(s).volumes().empty()) << "a render-hidden volume is left out of renders";
  c->undo(s);
  EXPECT_TRUE(s.find_volume("vol")->visible);
  EXPECT_TRUE(s.find_volume("vol")->render_visible);
  EXPECT_EQ(render_visible_scene(s).volumes().size(), 1u);
}

TEST(ObjectVisibility, RefusedLinesChangeNothing) {
  Scene s = two_objects();
  EXPECT_TRUE(test::throws_command_error(
      [&] { parse(R"({"cmd":"object.visibility","object":"nobody","viewport":false})")->redo(s); }, "object",
      "no object or volume named 'nobody'"));
  EXPECT_TRUE(test::throws_command_error([&] { parse(R"({"cmd":"object.visibility","object":"ball"})"); }, "viewport",
                                         "give 'viewport', 'render' or both"));
  EXPECT_EQ(test::command_field_of<ObjectVisibilityCommand>(
                s, json::parse(R"({"cmd":"object.visibility","object":"ball","viewport":"no"})")),
            "viewport");
  EXPECT_EQ(test::command_field_of<ObjectVisibilityCommand>(
                s, json::parse(R"({"cmd":"object.visibility","object":"ball","render":1})")),
            "render");
  EXPECT_EQ(test::command_field_of<ObjectVisibilityCommand>(s, json::parse(R"({"cmd":"object.visibility",
                                                                               "viewport":true})")),
            "object");
  for (const SceneObject& o : s.objects()) EXPECT_TRUE(o.visible && o.render_visible) << o.name;
}

}  // namespace object_visibility_test
}  // namespace trispline::core
