// place.sketch: the "extent" of the domain the object covers; a "springs" object through the registry and history, as a
// log replays it: the mass-spring contact surface spans a gap that the rays alone would sag into.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/scene/scene.h"
#include "editor/command_registry.h"
#include "editor/history.h"
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

}  // namespace place_sketch_test
}  // namespace trispline::core
