// lattice.certify (core/commands/lattice_certify.h) through the registry and the history: the teapot's ring lattice
// (periodic along u) gets a verdict that agrees with dense sampling of det J; a control point dragged through its
// neighbours makes it fold, and the reported points really fold; the query leaves the scene and the undo stack alone.
#include <gtest/gtest.h>

#include "core/commands/lattice_certify.h"
#include "core/placement/pressing.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/commands/history_test_util.h"

using namespace trispline;

namespace lattice_certify_test {

const nlohmann::json kTeapot = {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}};
const nlohmann::json kRing = {
    {"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}};
const nlohmann::json kCertify = {{"cmd", "lattice.certify"}, {"object", "t"}};

// Runs `line` as a replay would and returns its report.json statistics.
nlohmann::json run_stats(editor::History& history, const nlohmann::json& line) {
  test::run(history, line);
  return history.last_executed().stats();
}

double sampled_min_det(const core::TrivariateBSpline<glm::dvec3>& F, int n) {
  double mn = INFINITY;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        mn = std::min(mn, core::jacobian_determinant(F, glm::dvec3((i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n)));
  return mn;
}

TEST(LatticeCertify, RingVerdictAgreesWithSamplingAndLeavesTheSceneAlone) {
  core::Scene scene;
  editor::History history(scene);
  test::run(history, kTeapot);
  test::run(history, kRing);
  const core::SceneObject before = *scene.find("t");
  const std::size_t steps = history.size();
  const nlohmann::json stats = run_stats(history, kCertify);
  const double sampled = sampled_min_det(before.ffd->lattice, 20);
  EXPECT_EQ(stats.at("certificate"), sampled > 0.0 ? "fold_free" : "fold") << "sampled min det J " << sampled;
  EXPECT_EQ(stats.at("cells"), 16 * 1 * 3) << "spans: 16 around (periodic), 1 across (3 controls, order 3), 3 up";
  EXPECT_TRUE(stats.at("fold_cells").empty() == (stats.at("certificate") != "fold"));
  EXPECT_GE(stats.at("ms").get<double>(), 0.0);
  // A query: no undo step, nothing changed.
  EXPECT_EQ(history.size(), steps);
  EXPECT_EQ(scene.find("t")->ffd->lattice.control_points(), before.ffd->lattice.control_points());
  EXPECT_EQ(scene.find("t")->world_mesh->positions, before.world_mesh->positions);
}

TEST(LatticeCertify, AFoldIsFoundWhereDetJIsNonPositive) {
  core::Scene scene;
  editor::History history(scene);
  test::run(history, kTeapot);
  test::run(history, kRing);
  // Drag one inner control point across the ring to the far side: the lattice turns over there.
  const glm::dvec3 p = scene.find("t")->ffd->lattice.control_point(4, 1, 1);
  test::run(history,
            {{"cmd", "lattice.set_point"}, {"object", "t"}, {"index", {4, 1, 1}}, {"position", {-p.x, p.y, -p.z}}});
  const auto& F = scene.find("t")->ffd->lattice;
  ASSERT_LT(sampled_min_det(F, 24), 0.0) << "the drag folds the lattice";
  const nlohmann::json stats = run_stats(history, kCertify);
  ASSERT_EQ(stats.at("certificate"), "fold");
  ASSERT_FALSE(stats.at("fold_params").empty());
  for (std::size_t i = 0; i < stats.at("fold_params").size(); ++i) {
    const auto& t = stats.at("fold_params")[i];
    const glm::dvec3 uvw(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
    EXPECT_LE(core::jacobian_determinant(F, uvw), 1e-9);
    const auto& x = stats.at("fold_points")[i];
    EXPECT_LT(glm::length(glm::dvec3(x[0].get<double>(), x[1].get<double>(), x[2].get<double>()) - F.eval(uvw)), 1e-9);
  }
}

// lattice.press with keep_fold_free: a press strong enough to fold the ring is limited (bisection) to a strength whose
// lattice lattice.certify certifies; a lattice that folds already is refused, naming the field, scene untouched.
TEST(LatticeCertify, KeepFoldFreeLimitsAPressThatWouldFold) {
  core::Scene scene;
  editor::History history(scene);
  test::run(history, kTeapot);
  test::run(history, kRing);
  nlohmann::json press = {{"cmd", "lattice.press"}, {"object", "t"},   {"path", {{1.2, 0.3, 0.0}}},
                          {"radius", 0.6},          {"strength", 3.0}, {"falloff", "smooth"}};
  ASSERT_EQ(run_stats(history, kCertify).at("certificate"), "fold_free");
  test::run(history, press);
  ASSERT_EQ(run_stats(history, kCertify).at("certificate"), "fold") << "the plain press folds the ring";
  history.undo();
  press["keep_fold_free"] = true;
  const nlohmann::json st = run_stats(history, press);
  EXPECT_TRUE(st.at("limited").get<bool>());
  const double used = st.at("strength_used").get<double>();
  EXPECT_GT(used, 0.05) << "a real press remains";
  EXPECT_LT(used, 3.0);
  EXPECT_GT(st.at("certificates").get<int>(), 2);
  EXPECT_EQ(run_stats(history, kCertify).at("certificate"), "fold_free");
  // Folded already: nothing to keep.
  const glm::dvec3 p = scene.find("t")->ffd->lattice.control_point(4, 1, 1);
  test::run(history,
            {{"cmd", "lattice.set_point"}, {"object", "t"}, {"index", {4, 1, 1}}, {"position", {-p.x, p.y, -p.z}}});
  const auto before = scene.find("t")->ffd;
  EXPECT_TRUE(test::throws_command_error([&] { test::run(history, press); }, "keep_fold_free", "fold"));
  EXPECT_EQ(scene.find("t")->ffd, before) << "refused: the scene is untouched";
}

// A limited press leaves the lattice at the edge of folding. The same press again finds a smaller certified strength;
// when less than kMinMovableFraction of it can be certified the lattice cannot move that way: refused with the cell,
// scene untouched. A pull the other way still moves it, by its whole strength or the largest certified part.
TEST(LatticeCertify, KeepFoldFreeSaysWhenTheLatticeCannotMove) {
  core::Scene scene;
  editor::History history(scene);
  test::run(history, kTeapot);
  test::run(history, kRing);
  nlohmann::json press = {{"cmd", "lattice.press"}, {"object", "t"},      {"path", {{1.2, 0.3, 0.0}}}, {"radius", 0.6},
                          {"strength", 3.0},        {"falloff", "sharp"}, {"keep_fold_free", true}};
  std::vector<double> used;
  std::string refusal;
  for (int k = 0; k < 8 && refusal.empty(); ++k) {
    const auto before = scene.find("t")->ffd;
    try {
      used.push_back(run_stats(history, press).at("strength_used").get<double>());
      EXPECT_GE(used.back(), 3.0 * core::kMinMovableFraction) << "never a press that changes nothing visible";
      EXPECT_EQ(run_stats(history, kCertify).at("certificate"), "fold_free");
    } catch (const core::CommandError& e) {
      refusal = e.what();
      EXPECT_EQ(e.field(), "keep_fold_free");
      EXPECT_EQ(scene.find("t")->ffd, before) << "refused: the scene is untouched";
    }
  }
  ASSERT_FALSE(used.empty());
  EXPECT_NE(refusal.find("cannot move this way"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("in cell ("), std::string::npos) << refusal;
  nlohmann::json pull = press;
  pull["strength"] = -1.0;
  const nlohmann::json st = run_stats(history, pull);
  EXPECT_LT(st.at("strength_used").get<double>(), -1.0 * core::kMinMovableFraction);
  EXPECT_EQ(run_stats(history, kCertify).at("certificate"), "fold_free");
}

TEST(LatticeCertify, ErrorsNameTheirField) {
  core::Scene scene;
  editor::History history(scene);
  test::run(history, kTeapot);
  EXPECT_TRUE(test::throws_command_error([&] { test::run(history, kCertify); }, "object", "lattice"));
  test::run(history, kRing);
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        test::run(history, {{"cmd", "lattice.certify"}, {"object", "t"}, {"max_depth", 13}});
      },
      "max_depth", ""));
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        test::run(history, {{"cmd", "lattice.certify"}, {"object", "nope"}});
      },
      "object", "nope"));
}

}  // namespace lattice_certify_test
