// dffd.split (core/commands/dffd_split.h): a sphere split around a cylinder — the command keeps the rest mesh and
// adds a rig, the world mesh is split and capped, stats report the construction, anim.keyframe walks it, undo
// restores the object bit for bit, bad input names the field and changes nothing.
#include <gtest/gtest.h>

#include "core/commands/anim_commands.h"
#include "core/commands/dffd_split.h"
#include "core/commands/scene_primitive.h"

namespace trispline::core {
namespace dffd_split_test {

using nlohmann::json;

Scene ball_and_tool() {
  Scene s;
  CommandContext ctx;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"), ctx)->redo(s);
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"cylinder","name":"tool",
      "scale":[0.3,1.6,0.3],"translate":[0.013,0,0.017]})"),
                               ctx)
      ->redo(s);
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"huge",
      "scale":[0.2,5,0.2],"translate":[0.5,0,0]})"),
                               ctx)
      ->redo(s);
  return s;
}

const char* kSplit = R"({"cmd":"dffd.split","object":"ball","obstacles":["tool"],"axis":"x","w_axis":"y",
    "order":[3,3,3],"controls":[16,12,12],"kernel":"gaussian","kernel_width":0.7,"openings":"cap"})";

TEST(DffdSplit, SplitsCapsReportsAndUndoesBitForBit) {
  Scene s = ball_and_tool();
  const Scene before = s;
  CommandContext ctx;
  auto c = DffdSplitCommand::parse(json::parse(kSplit), ctx);
  c->redo(s);
  const SceneObject& ball = *s.find("ball");
  ASSERT_TRUE(ball.dffd);
  EXPECT_FALSE(ball.ffd);
  EXPECT_EQ(ball.rest_mesh, before.find("ball")->rest_mesh);  // the rest mesh is kept; the split is evaluated
  EXPECT_GT(ball.world_mesh->vertex_count(), ball.rest_mesh->vertex_count());
  const json st = c->stats();
  EXPECT_EQ(st.at("discontinuities"), 1);
  EXPECT_EQ(st.at("fold_overs"), 0);
  EXPECT_GT(st.at("cut_edges").get<int>(), 10);
  EXPECT_GT(st.at("cap_triangles").get<int>(), 10);
  EXPECT_EQ(st.at("open_chains"), 0);
  EXPECT_EQ(st.at("vertices_after").get<std::size_t>(), ball.world_mesh->vertex_count());
  // The round trip through the log keeps every field.
  const std::shared_ptr<const TriMesh> split_mesh = ball.world_mesh;
  const json again = DffdSplitCommand::parse(c->to_json(), ctx)->to_json();
  EXPECT_EQ(again, c->to_json());
  // Walk: keys on the offset (anim.keyframe accepts DFFD objects).
  AnimKeyframeCommand::parse(json::parse(R"({"cmd":"anim.keyframe","object":"ball","frame":1,"offset":[-1.5,0,0]})"),
                             ctx)
      ->redo(s);
  AnimKeyframeCommand::parse(json::parse(R"({"cmd":"anim.keyframe","object":"ball","frame":49,"offset":[1.5,0,0]})"),
                             ctx)
      ->redo(s);
  EXPECT_TRUE(s.find("ball")->dffd_animated());
  EXPECT_EQ(s.find("ball")->world_mesh->vertex_count(), before.find("ball")->world_mesh->vertex_count());
  // Undo (of the split, after undoing the keys): the object is exactly what it was.
  Scene back = before;
  auto c2 = DffdSplitCommand::parse(json::parse(kSplit), ctx);
  c2->redo(back);
  c2->undo(back);
  const SceneObject& b = *back.find("ball");
  EXPECT_FALSE(b.dffd);
  EXPECT_EQ(b.rest_mesh, before.find("ball")->rest_mesh);
  EXPECT_EQ(b.world_mesh->positions, before.find("ball")->world_mesh->positions);
  EXPECT_EQ(b.world_mesh->triangles, before.find("ball")->world_mesh->triangles);
  // Redo gives the same split mesh bit for bit (deterministic).
  c2->redo(back);
  EXPECT_EQ(back.find("ball")->world_mesh->positions, split_mesh->positions);
}

TEST(DffdSplit, BadInputNamesTheFieldAndChangesNothing) {
  Scene s = ball_and_tool();
  const Scene before = s;
  CommandContext ctx;
  const auto expect_field = [&](const std::string& line, const char* field) {
    try {
      DffdSplitCommand::parse(json::parse(line), ctx)->redo(s);
      ADD_FAILURE() << line << " was accepted";
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    EXPECT_FALSE(s.find("ball")->dffd);
    EXPECT_EQ(s.find("ball")->world_mesh, before.find("ball")->world_mesh);
  };
  json j = json::parse(kSplit);
  auto with = [&](const char* key, const json& v) {
    json k = j;
    k[key] = v;
    return k.dump();
  };
  expect_field(with("object", "nobody"), "object");
  expect_field(with("obstacles", json::array({"ghost"})), "obstacles");
  expect_field(with("obstacles", json::array({"ball"})), "obstacles");
  expect_field(with("obstacles", json::array()), "obstacles");
  expect_field(with("w_axis", "x"), "w_axis");
  expect_field(with("kernel_width", 0), "kernel_width");
  expect_field(with("kernel_width", 0.02), "kernel_width");  // folds (seed Theorem 6)
  expect_field(with("openings", "glue"), "openings");
  expect_field(with("order", json::array({9, 3, 3})), "order");
  expect_field(with("controls", json::array({2, 12, 12})), "controls");
  json box = j;  // the obstacle is larger than the lattice box
  box["box"] = {{"lo", {-1.5, -1.2, -1.2}}, {"hi", {1.5, 1.2, 1.2}}};
  expect_field(box.dump(), "box");
}

}  // namespace dffd_split_test
}  // namespace trispline::core
