// dffd.cut (core/commands/dffd_cut.h): a placed sphere cut at u = 0.5 and opened — the halves separate by the gap
// with no vertex in between, the only boundary is the cut, undo restores everything bit for bit, bad input changes
// nothing.
#include <gtest/gtest.h>

#include <map>

#include "core/commands/camera_set.h"
#include "core/commands/dffd_cut.h"
#include "core/commands/place_sketch.h"
#include "core/commands/scene_primitive.h"

namespace trispline::core {
namespace dffd_cut_test {

using nlohmann::json;

void run(Scene& s, CommandPtr c) { c->redo(s); }

Scene placed_ball() {
  Scene s;
  CommandContext ctx;
  run(s, ScenePrimitiveCommand::parse(
             json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":3})"), ctx));
  run(s, ScenePrimitiveCommand::parse(
             json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","scale":[0.5,0.2,0.2]})"), ctx));
  run(s, CameraSetCommand::parse(json::parse(R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],
                                                 "fov_deg":45,"viewport":[800,600]})"),
                                 ctx));
  run(s, PlaceSketchCommand::parse(json::parse(R"({"cmd":"place.sketch","stroke":[[250,360],[400,350],[550,360]],
      "object":"ball","width":0.3,"height":0.3,"samples":[24,8],"order":[4,4,3],"controls":[8,4,3],"fit":"stretch"})"),
                                   ctx));
  return s;
}

TEST(DffdCut, HalvesSeparateByTheGapAndOnlyTheCutIsOpen) {
  Scene s = placed_ball();
  const Scene before = s;
  CommandContext ctx;
  auto cut =
      DffdCutCommand::parse(json::parse(R"({"cmd":"dffd.cut","object":"ball","axis":"u","at":0.5,"gap":0.3})"), ctx);
  cut->redo(s);
  const SceneObject& ball = *s.find("ball");
  const std::size_t nv = ball.rest_mesh->positions.size();
  ASSERT_GT(nv, before.find("ball")->rest_mesh->positions.size());
  ASSERT_EQ(ball.ffd->params.size(), nv);
  // The sphere has a meridian exactly at the cut: its vertices are duplicated, the other crossing edges cut.
  EXPECT_GT(cut->stats().at("cut_edges").get<int>() + cut->stats().at("duplicated_on_plane").get<int>(), 8);
  // The two halves along the stroke (x grows along it): apart by most of the 0.3 gap (the cut's rim is not exactly
  // perpendicular to x on the arched stroke), no vertex inside it. Without the cut they touch (checked below).
  double minus_max = -1e9, plus_min = 1e9;
  for (std::size_t v = 0; v < nv; ++v) {
    const double x = ball.world_mesh->positions[v].x;
    if (ball.ffd->params[v].x < 0.5)
      minus_max = std::max(minus_max, x);
    else
      plus_min = std::min(plus_min, x);
  }
  EXPECT_GT(plus_min - minus_max, 0.15) << minus_max << " " << plus_min;
  // Boundary edges (one face) exist only at the cut: both ends at u = 0.5 ∓ eps.
  std::map<std::pair<int, int>, int> faces;
  for (const auto& t : ball.rest_mesh->triangles)
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      ++faces[{std::min(a, b), std::max(a, b)}];
    }
  int boundary = 0;
  for (const auto& [edge, n] : faces) {
    EXPECT_LE(n, 2);
    if (n != 1) continue;
    ++boundary;
    EXPECT_NEAR(std::abs(ball.ffd->params[edge.first].x - 0.5), 1e-6, 1e-12);
    EXPECT_NEAR(std::abs(ball.ffd->params[edge.second].x - 0.5), 1e-6, 1e-12);
  }
  EXPECT_GT(boundary, 8);
  // The same cut with gap 0 splits the topology but leaves the surface closed in space.
  Scene closed = before;
  DffdCutCommand::parse(json::parse(R"({"cmd":"dffd.cut","object":"ball","at":0.5})"), ctx)->redo(closed);
  double m0 = -1e9, p0 = 1e9;
  for (std::size_t v = 0; v < closed.find("ball")->ffd->params.size(); ++v) {
    const double x = closed.find("ball")->world_mesh->positions[v].x;
    if (closed.find("ball")->ffd->params[v].x < 0.5)
      m0 = std::max(m0, x);
    else
      p0 = std::min(p0, x);
  }
  EXPECT_LT(std::abs(p0 - m0), 0.05);
  cut->undo(s);
  EXPECT_EQ(s.find("ball")->rest_mesh, before.find("ball")->rest_mesh);
  EXPECT_EQ(s.find("ball")->ffd, before.find("ball")->ffd);
  EXPECT_EQ(s.find("ball")->world_mesh->positions, before.find("ball")->world_mesh->positions);
}

TEST(DffdCut, BadParametersNameTheFieldAndChangeNothing) {
  Scene s = placed_ball();
  CommandContext ctx;
  auto cut = DffdCutCommand::parse(json::parse(R"({"cmd":"dffd.cut","object":"ball","at":0.5})"), ctx);
  cut->redo(s);
  const Scene once = s;
  const auto expect_field = [&](const char* line, const char* field) {
    try {
      auto c = DffdCutCommand::parse(json::parse(line), ctx);
      c->redo(s);
      ADD_FAILURE() << line << " was accepted";
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    EXPECT_EQ(s.find("ball")->ffd, once.find("ball")->ffd);
    EXPECT_EQ(s.find("ball")->rest_mesh, once.find("ball")->rest_mesh);
  };
  expect_field(R"({"cmd":"dffd.cut","object":"ball","at":1.5})", "at");        // outside the domain
  expect_field(R"({"cmd":"dffd.cut","object":"ball","at":0.5})", "at");        // already a discontinuity
  expect_field(R"({"cmd":"dffd.cut","object":"ground","at":0.5})", "object");  // no lattice
  expect_field(R"({"cmd":"dffd.cut","object":"ball","at":0.3,"gap":1e9})", "gap");
  expect_field(R"({"cmd":"dffd.cut","object":"ball","at":0.3,"eps":0})", "eps");
  expect_field(R"({"cmd":"dffd.cut","object":"ball","axis":"q","at":0.3})", "axis");
}

}  // namespace dffd_cut_test
}  // namespace trispline::core
