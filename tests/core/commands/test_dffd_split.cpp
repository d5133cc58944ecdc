// dffd.split (core/commands/dffd_split.h): a sphere split around a cylinder — the command keeps the rest mesh and
// adds a rig, the world mesh is split and capped, stats report the construction, anim.keyframe walks it, undo
// restores the object bit for bit, bad input names the field and changes nothing; no vertex is left inside an
// obstacle (the real mushroom of CGAL's data around a bar when the asset corpus is there).
#include <gtest/gtest.h>

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/dffd_split.h"
#include "core/commands/scene_load.h"
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

// Vertices strictly inside the tool cylinder of ball_and_tool (its 64-gon's inscribed circle, with a margin).
std::size_t inside_tool(const TriMesh& m) {
  const double inscribed = 0.3 * std::cos(3.14159265358979323846 / 64.0) - 1e-9;
  std::size_t n = 0;
  for (const glm::dvec3& p : m.positions)
    n += std::abs(p.y) < 1.6 && glm::length(glm::dvec2(p.x - 0.013, p.z - 0.017)) < inscribed;
  return n;
}

TEST(DffdSplit, NoVertexStaysInsideTheObstacle) {
  for (const char* openings : {"open", "stitch", "cap"}) {
    Scene s = ball_and_tool();
    json line = json::parse(kSplit);
    line["openings"] = openings;
    CommandContext ctx;
    auto c = DffdSplitCommand::parse(line, ctx);
    c->redo(s);
    const json st = c->stats();
    // The seed's construction fits the rows to the cross-section only at their own v and w: it leaves vertices
    // inside, and the command refines until none is.
    EXPECT_GT(st.at("inside_before_refinement").get<int>(), 0) << openings;
    EXPECT_GE(st.at("refinement_rounds").get<int>(), 1) << openings;
    EXPECT_EQ(st.at("inside_obstacle"), 0) << openings;
    EXPECT_GT(st.at("clearance_used").get<double>(), 0.0) << openings;
    EXPECT_TRUE(st.at("unchecked_obstacles").empty());
    EXPECT_EQ(inside_tool(*s.find("ball")->world_mesh), 0u) << openings;  // checked apart from CGAL
    // The log line is the user's: replaying it refines the same way, bit for bit.
    EXPECT_EQ(c->to_json().at("controls"), json::array({16, 12, 12}));
    Scene again = ball_and_tool();
    DffdSplitCommand::parse(c->to_json(), ctx)->redo(again);
    EXPECT_EQ(again.find("ball")->world_mesh->positions, s.find("ball")->world_mesh->positions);
  }
  // The seam's two states clear the tool alike: a capped and a stitched split refine the same lattice.
  Scene cap = ball_and_tool(), stitch = ball_and_tool();
  CommandContext ctx;
  json line = json::parse(kSplit);
  auto c1 = DffdSplitCommand::parse(line, ctx);
  c1->redo(cap);
  line["openings"] = "stitch";
  auto c2 = DffdSplitCommand::parse(line, ctx);
  c2->redo(stitch);
  EXPECT_EQ(c1->stats().at("controls_used"), c2->stats().at("controls_used"));
  EXPECT_EQ(c1->stats().at("clearance_used"), c2->stats().at("clearance_used"));
}

TEST(DffdSplit, AnObstacleThatBoundsNoVolumeIsListedUnchecked) {
  Scene s = ball_and_tool();
  CommandContext ctx;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"sheet",
      "scale":[0.3,1,0.3],"rotate_deg":[0,0,90]})"),
                               ctx)
      ->redo(s);
  json line = json::parse(kSplit);
  line["obstacles"] = json::array({"sheet"});
  line["openings"] = "open";
  auto c = DffdSplitCommand::parse(line, ctx);
  c->redo(s);
  EXPECT_EQ(c->stats().at("unchecked_obstacles"), json::array({"sheet"}));
  EXPECT_EQ(c->stats().at("inside_obstacle"), 0);
  EXPECT_EQ(c->stats().at("refinement_rounds"), 0);
}

#if defined(TRISPLINE_HAVE_CORPUS)
// A real mushroom (CGAL's data/meshes/mushroom.off, an open surface: openings open) split around a bar with a
// 12 × 8 × 6 lattice: the seed's construction leaves vertices inside the bar.
TEST(DffdSplit, TheRealMushroomClearsTheBar) {
  Scene s;
  CommandContext ctx;
  json load = {{"cmd", "scene.load"},
               {"name", "mushroom"},
               {"path", std::string(TRISPLINE_SOURCE_DIR) + "/assets/data/corpus/cgal/mushroom.off"}};
  SceneLoadCommand::parse(load, ctx)->redo(s);
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"bar",
      "scale":[0.05,0.05,0.5],"translate":[0,0.1,0]})"),
                               ctx)
      ->redo(s);
  auto c = DffdSplitCommand::parse(json::parse(R"({"cmd":"dffd.split","object":"mushroom","obstacles":["bar"],
      "axis":"x","w_axis":"y","order":[3,3,3],"controls":[12,8,6],"kernel_width":0.3,"openings":"open"})"),
                                   ctx);
  c->redo(s);
  EXPECT_GT(c->stats().at("inside_before_refinement").get<int>(), 0);
  EXPECT_EQ(c->stats().at("inside_obstacle"), 0);
  std::size_t inside = 0;
  for (const glm::dvec3& p : s.find("mushroom")->world_mesh->positions)
    inside += std::abs(p.x) < 0.05 - 1e-9 && std::abs(p.y - 0.1) < 0.05 - 1e-9 && std::abs(p.z) < 0.5 - 1e-9;
  EXPECT_EQ(inside, 0u);
}
#endif

}  // namespace dffd_split_test
}  // namespace trispline::core
