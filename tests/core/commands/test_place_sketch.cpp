// place.sketch: the "extent" of the domain the object covers; a "springs" object through the registry and history, as a
// log replays it: the mass-spring contact surface spans a gap that the rays alone would sag into.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/scene/scene.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/history_test_util.h"
#include "tests/core/commands/placed_crate.h"

using namespace trispline;

namespace place_sketch_test {

using test::run;

// Replays tests/logs/bridge_springs.jsonl, optionally without the placement's "springs" object, and returns the
// lowest contact-surface point F(u, v, 0) over the gap between the blocks (|x| < 0.25) and over everything.
struct BridgeResult {
  double min_gap_y = 1e9, min_y = 1e9;
};
BridgeResult replay_bridge(bool springs) {
  core::Scene scene;
  editor::History history{scene};
  std::ifstream in(std::string(TRISPLINE_SOURCE_DIR) + "/tests/logs/bridge_springs.jsonl");
  std::string text;
  while (std::getline(in, text)) {
    if (text.empty() || text[0] == '#') continue;
    nlohmann::json line = nlohmann::json::parse(text);
    if (!springs) line.erase("springs");
    run(history, line);
  }
  const core::TrivariateBSpline<glm::dvec3>& F = scene.find("plank")->ffd->lattice;
  BridgeResult r;
  for (int a = 0; a <= 200; ++a)
    for (int b = 0; b <= 4; ++b) {
      const glm::dvec3 p = F.eval({a / 200.0, b / 4.0, 0.0});
      r.min_y = std::min(r.min_y, p.y);
      if (std::abs(p.x) < 0.25) r.min_gap_y = std::min(r.min_gap_y, p.y);
    }
  return r;
}

TEST(Bridging, SpringsKeepTheContactSurfaceUpAcrossTheGap) {
  const BridgeResult sagging = replay_bridge(false), bridged = replay_bridge(true);
  // Without springs the contact surface follows the rays down into the gap (ground at y = 0, block tops at 0.3).
  EXPECT_LT(sagging.min_gap_y, 0.1);
  // With them it spans the gap like a stiff plank, resting on the blocks, and nothing goes below the ground.
  EXPECT_GT(bridged.min_gap_y, 0.2);
  EXPECT_GT(bridged.min_y, -1e-6);
}

}  // namespace place_sketch_test

namespace trispline::core {
namespace place_sketch_test {

using nlohmann::json;
using test::place_line;
using test::placed_crate;

TEST(PlaceSketchExtent, ObjectCoversTheGivenFractionOfTheDomain) {
  const Scene s = placed_crate(0.4);
  const FfdBinding& b = *s.find("crate")->ffd;
  double umin = 1e9, umax = -1e9;
  for (const auto& p : b.params) umin = std::min(umin, p.x), umax = std::max(umax, p.x);
  EXPECT_NEAR(umin, 0.0, 1e-12);
  EXPECT_NEAR(umax, 0.4, 1e-12);
  CommandContext ctx;
  json bad = place_line(1.0);
  bad["extent"] = 0.0;
  EXPECT_THROW(PlaceSketchCommand::parse(bad, ctx), CommandError);
  bad["extent"] = 1.5;
  EXPECT_THROW(PlaceSketchCommand::parse(bad, ctx), CommandError);
}

// The placed mesh's extent along x (the stroke) and y (up), world units.
glm::dvec2 length_and_height(const Scene& s) {
  const TriMesh& m = *s.find("crate")->world_mesh;
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return {hi.x - lo.x, hi.y - lo.y};
}

// A 1.0 × 0.4 × 0.4 crate over flat ground along a long straight stroke drawn looking straight down (so the band's
// width does not skew it along the stroke, as a perspective view of the ground would), placed with `fit`.
Scene crate_on_a_long_stroke(const std::string& fit, json* report = nullptr) {
  Scene s;
  test::run_crate_line(s, json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":4})"));
  test::run_crate_line(s,
                       json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"crate","scale":[0.5,0.2,0.2]})"));
  test::run_crate_line(s, json::parse(R"({"cmd":"camera.set","eye":[0,5,0],"target":[0,0,0],"up":[0,0,-1],
                         "fov_deg":45,"viewport":[800,600]})"));
  json line = json::parse(R"({"cmd":"place.sketch","stroke":[[100,330],[400,330],[700,330]],"object":"crate",
    "width":0.3,"height":0.2,"samples":[32,8],"order":[4,4,3],"controls":[8,4,3],"volume":"offset"})");
  if (!fit.empty()) line["fit"] = fit;
  const CommandPtr cmd = test::run_crate_line(s, line);
  if (report) *report = cmd->stats();
  return s;
}

TEST(PlaceSketchFit, KeepHoldsTheObjectsProportionsOnALongStraightStroke) {
  json report;
  const Scene keep = crate_on_a_long_stroke("", &report);  // keep is the default
  const glm::dvec2 k = length_and_height(keep);

  const double original = 1.0 / 0.4;
  EXPECT_NEAR(k.x / k.y, original, 0.1 * original) << "length " << k.x << ", height " << k.y;
  EXPECT_NEAR(k.y, 0.2, 0.02) << "the height is the placement's h";
  // The report says what was chosen: the part of the path that holds the object's length scaled as its height
  // (1.0 · 0.2 / 0.4 = 0.5 of a path over 2).
  EXPECT_EQ(report.at("fit"), "keep");
  ASSERT_GT(report.at("path_length").get<double>(), 2.0) << "a long stroke";
  EXPECT_GT(report.at("extent").get<double>(), 0.0);
  EXPECT_LT(report.at("extent").get<double>(), 0.5);
  // stretch: today's behaviour, the crate smeared along the whole stroke.
  json stretched_report;
  const glm::dvec2 st = length_and_height(crate_on_a_long_stroke("stretch", &stretched_report));
  EXPECT_GT(st.x / st.y, 2.0 * original);
  EXPECT_EQ(stretched_report.at("extent").get<double>(), 1.0);
}

TEST(PlaceSketchFit, KeepIsCappedByExtentAndUnknownFitsAreRefused) {
  CommandContext ctx;
  json line = test::place_line(1.0);
  line["fit"] = "squash";
  EXPECT_THROW(PlaceSketchCommand::parse(line, ctx), CommandError);
  // A short stroke: keep would make the crate longer than the path, so it covers the whole of it (extent 1).
  Scene s;
  test::run_crate_line(s, json::parse(R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":4})"));
  test::run_crate_line(s,
                       json::parse(R"({"cmd":"scene.primitive","kind":"box","name":"crate","scale":[0.5,0.2,0.2]})"));
  test::run_crate_line(s, json::parse(R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],
                         "fov_deg":45,"viewport":[800,600]})"));
  const CommandPtr cmd = test::run_crate_line(s, json::parse(R"({"cmd":"place.sketch","stroke":[[380,330],[420,330]],
    "object":"crate","width":0.3,"height":0.2,"samples":[16,8],"order":[4,4,3],"controls":[8,4,3]})"));
  EXPECT_EQ(cmd->stats().at("extent").get<double>(), 1.0);
}

}  // namespace place_sketch_test
}  // namespace trispline::core
