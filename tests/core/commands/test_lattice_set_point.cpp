// lattice.set_point (core/commands/lattice_set_point.h) as a log replays it, through the registry and the history:
// one control point of the teapot's ring lattice moves to an exact world position and the mesh follows, undo
// restores the lattice and the mesh bit for bit, a bad index or position names its field and leaves the scene as
// the ring left it.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/commands/lattice_set_point.h"
#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/commands/history_test_util.h"
#include "tests/test_paths.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace lattice_set_point_test {

const nlohmann::json kTeapot = {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "t"}, {"scale", 0.3}};
const nlohmann::json kRing = {
    {"cmd", "lattice.ring"}, {"object", "t"}, {"radius", 1.2}, {"controls", {16, 3, 4}}, {"order", {4, 3, 2}}};

using test::logs_dir, test::run;

// The teapot on its ring lattice, before any point moved.
struct RingScene {
  RingScene() {
    run(history, kTeapot);
    run(history, kRing);
  }
  core::Scene scene;
  editor::History history{scene};
};

// Runs the lines of `log` until one throws; returns that line's 1-based number in the file and its CommandError
// (0 and an error blaming no field when every line ran).
std::pair<int, core::CommandError> run_log(editor::History& history, const fs::path& log) {
  for (const editor::LogLine& line : editor::read_log(log)) {
    try {
      run(history, line.json);
    } catch (const core::CommandError& e) {
      return {line.number, e};
    }
  }
  return {0, core::CommandError("")};
}

TEST(LatticeSetPoint, LogMovesOnePointExactlyAndUndoRestoresBitForBit) {
  core::Scene scene;
  editor::History history(scene);
  const auto [failed, error] = run_log(history, logs_dir() / "set_point.jsonl");
  ASSERT_EQ(failed, 0) << error.what();
  const core::SceneObject& t = *scene.find("t");
  EXPECT_EQ(t.ffd->lattice.control_point(2, 1, 3), glm::dvec3(0.9, 0.75, 0.5));
  // Against the lattice before: exactly one control point differs, and the mesh follows.
  const RingScene before;
  const auto& a = before.scene.find("t")->ffd->lattice.control_points();
  const auto& b = t.ffd->lattice.control_points();
  ASSERT_EQ(a.size(), b.size());
  int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i] != b[i];
  EXPECT_EQ(differ, 1);
  EXPECT_NE(t.world_mesh->positions, before.scene.find("t")->world_mesh->positions);
  // Undo the camera and the set_point: the lattice and the mesh are bit for bit the ring's.
  const std::vector<glm::dvec3> moved_mesh = t.world_mesh->positions;
  history.undo();
  history.undo();
  EXPECT_EQ(scene.find("t")->ffd->lattice.control_points(), a);
  EXPECT_EQ(scene.find("t")->world_mesh->positions, before.scene.find("t")->world_mesh->positions);
  history.redo();
  EXPECT_EQ(scene.find("t")->world_mesh->positions, moved_mesh) << "redo is deterministic";
}

TEST(LatticeSetPoint, LineRoundTripsAndStatsSayWhatMoved) {
  RingScene r;
  const nlohmann::json line = {
      {"cmd", "lattice.set_point"}, {"object", "t"}, {"index", {2, 1, 3}}, {"position", {0.9, 0.75, 0.5}}};
  const core::CommandContext ctx;
  auto c = core::LatticeSetPointCommand::parse(line, ctx);
  EXPECT_EQ(c->to_json(), line);
  const glm::dvec3 old = r.scene.find("t")->ffd->lattice.control_point(2, 1, 3);
  c->redo(r.scene);
  EXPECT_EQ(c->stats().at("moved"), 1);
  EXPECT_DOUBLE_EQ(c->stats().at("displacement").get<double>(), glm::length(glm::dvec3(0.9, 0.75, 0.5) - old));
  // Moving a point to where it already is moves nothing.
  nlohmann::json same = line;
  same["index"] = {0, 0, 0};
  const glm::dvec3 p = r.scene.find("t")->ffd->lattice.control_point(0, 0, 0);
  same["position"] = {p.x, p.y, p.z};
  auto still = core::LatticeSetPointCommand::parse(same, ctx);
  still->redo(r.scene);
  EXPECT_EQ(still->stats().at("moved"), 0);
}

TEST(LatticeSetPoint, BadIndexAndNonFinitePositionNameTheFieldAndLeaveTheSceneUntouched) {
  struct Case {
    const char* log;
    const char* field;
  };
  for (const Case c : {Case{"bad_set_point_index.jsonl", "index"}, Case{"bad_set_point_nan.jsonl", "position"}}) {
    core::Scene scene;
    editor::History history(scene);
    const auto [failed, error] = run_log(history, logs_dir() / c.log);
    EXPECT_EQ(failed, 3) << c.log;
    EXPECT_EQ(error.field(), c.field) << error.what();
    EXPECT_NE(std::string(error.what()).find(std::string("field '") + c.field + "'"), std::string::npos)
        << error.what();
    EXPECT_EQ(history.applied(), 2u);
    const RingScene ring;
    EXPECT_EQ(scene.find("t")->ffd->lattice.control_points(), ring.scene.find("t")->ffd->lattice.control_points())
        << c.log;
    EXPECT_EQ(scene.find("t")->world_mesh->positions, ring.scene.find("t")->world_mesh->positions) << c.log;
  }
  core::CommandContext ctx;
  EXPECT_THROW(editor::CommandRegistry::builtin().parse(
                   {{"cmd", "lattice.set_point"}, {"object", "t"}, {"index", {1, 2}}, {"position", {0, 0, 0}}}, ctx),
               core::CommandError);
}

TEST(LatticeSetPoint, ErrorsNameTheObjectOrTheLatticeSize) {
  RingScene r;
  run(r.history, {{"cmd", "scene.primitive"}, {"kind", "sphere"}, {"name", "ball"}});
  const core::Scene before = r.scene;
  const auto line = [](const char* object, glm::ivec3 i) {
    return nlohmann::json{
        {"cmd", "lattice.set_point"}, {"object", object}, {"index", {i.x, i.y, i.z}}, {"position", {0, 0, 0}}};
  };
  EXPECT_EQ(test::command_field_of<core::LatticeSetPointCommand>(r.scene, line("nobody", {0, 0, 0})), "object");
  EXPECT_EQ(test::command_field_of<core::LatticeSetPointCommand>(r.scene, line("ball", {0, 0, 0})), "object");
  EXPECT_EQ(test::command_field_of<core::LatticeSetPointCommand>(r.scene, line("t", {0, -1, 0})), "index");
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        core::LatticeSetPointCommand::parse(line("t", {0, 0, 4}), {})->redo(r.scene);
      },
      "index", "outside the 16 x 3 x 4 control points of 't'"));
  test::expect_same_meshes(r.scene, before);
  EXPECT_EQ(r.scene.find("t")->ffd, before.find("t")->ffd);
}

}  // namespace lattice_set_point_test
