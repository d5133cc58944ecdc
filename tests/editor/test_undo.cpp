// Undo/redo and determinism: N commands then N undos restore the original meshes bit for bit; N redos equal a
// straight replay; two replays of one log give identical meshes.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "tests/test_paths.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

using test::logs_dir;

bool bit_equal(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::dvec3)) == 0);
}

// Asserts both scenes hold the same objects in the same order with bit-identical meshes.
void expect_same_meshes(const core::Scene& a, const core::Scene& b) {
  ASSERT_EQ(a.objects().size(), b.objects().size());
  for (std::size_t i = 0; i < a.objects().size(); ++i) {
    const auto& x = a.objects()[i];
    const auto& y = b.objects()[i];
    EXPECT_EQ(x.name, y.name);
    ASSERT_TRUE(x.world_mesh && y.world_mesh);
    EXPECT_TRUE(bit_equal(x.world_mesh->positions, y.world_mesh->positions)) << x.name << " positions differ";
    EXPECT_TRUE(bit_equal(x.world_mesh->normals, y.world_mesh->normals)) << x.name << " normals differ";
    EXPECT_EQ(x.world_mesh->triangles, y.world_mesh->triangles) << x.name;
  }
}

core::CommandPtr parse(const char* text) {
  core::CommandContext ctx;
  ctx.base_dir = logs_dir();
  return editor::CommandRegistry::builtin().parse(nlohmann::json::parse(text), ctx);
}

const char* kSetup[] = {
    R"({"cmd":"scene.primitive","kind":"terrain","name":"hills","scale":[2,1,2],"seed":7})",
    R"({"cmd":"scene.primitive","kind":"box","name":"crate","scale":[0.4,0.15,0.15],"translate":[0,1.5,0]})",
    R"({"cmd":"camera.set","eye":[0,3.5,3.5],"target":[0,0,0],"fov_deg":45,"viewport":[800,600]})",
};

const char* kEdits[] = {
    R"({"cmd":"place.sketch","object":"crate","stroke":[[250,330],[400,300],[550,330]],"width":0.3,"height":0.25,
        "samples":[24,8],"volume":"extrude","order":[4,4,3],"controls":[8,4,3],"length_axis":"x","up_axis":"y"})",
    R"({"cmd":"place.sketch","object":"crate","stroke":[[260,400],[400,360],[540,400]],"width":0.4,"height":0.3,
        "samples":[32,8],"volume":"offset","order":[3,3,2],"controls":[10,4,2],"length_axis":"x","up_axis":"y"})",
    R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","scale":0.3,"translate":[0.5,0.5,0]})",
    R"({"cmd":"scene.remove","name":"hills"})",
};

TEST(Undo, NCommandsThenNUndosRestoreBitForBit_NRedosEqualStraightReplay) {
  core::Scene scene;
  editor::History history(scene);
  for (const char* s : kSetup) history.execute(parse(s));
  const core::Scene original = scene;

  for (const char* s : kEdits) history.execute(parse(s));
  const core::Scene after = scene;
  ASSERT_NE(after.find("crate")->world_mesh->positions, original.find("crate")->world_mesh->positions);

  for (std::size_t i = 0; i < std::size(kEdits); ++i) history.undo();
  expect_same_meshes(scene, original);

  for (std::size_t i = 0; i < std::size(kEdits); ++i) history.redo();
  expect_same_meshes(scene, after);

  // A straight replay in a fresh scene gives the same meshes as the redone history.
  core::Scene fresh;
  editor::History straight(fresh);
  for (const char* s : kSetup) straight.execute(parse(s));
  for (const char* s : kEdits) straight.execute(parse(s));
  expect_same_meshes(fresh, after);
}

TEST(Undo, FailedCommandLeavesSceneUntouchedAndHistoryUnchanged) {
  core::Scene scene;
  editor::History history(scene);
  for (const char* s : kSetup) history.execute(parse(s));
  const core::Scene before = scene;
  const std::size_t applied = history.applied();
  // Width 0 is rejected by the placement.
  EXPECT_THROW(history.execute(parse(
                   R"({"cmd":"place.sketch","object":"crate","stroke":[[250,330],[550,330]],"width":0,"height":0.2,
                       "samples":[16,8],"volume":"extrude","order":[3,3,2],"controls":[6,3,2],"length_axis":"x",
                       "up_axis":"y"})")),
               core::CommandError);
  EXPECT_EQ(history.applied(), applied);
  expect_same_meshes(scene, before);
}

TEST(Undo, JumpToMovesThroughHistory) {
  core::Scene scene;
  editor::History history(scene);
  for (const char* s : kSetup) history.execute(parse(s));
  for (const char* s : kEdits) history.execute(parse(s));
  history.jump_to(1);
  EXPECT_EQ(scene.objects().size(), 1u);
  history.jump_to(history.size());
  EXPECT_EQ(history.applied(), history.size());
  EXPECT_NE(scene.find("ball"), nullptr);
  EXPECT_EQ(scene.find("hills"), nullptr);
}

TEST(Determinism, TwoReplaysGiveIdenticalMeshes) {
  for (const char* name : {"place_on_plane.jsonl", "undo_redo.jsonl"}) {
    core::Scene a, b;
    editor::History ha(a), hb(b);
    ASSERT_TRUE(editor::replay_lines(ha, logs_dir() / name).ok) << name;
    ASSERT_TRUE(editor::replay_lines(hb, logs_dir() / name).ok) << name;
    expect_same_meshes(a, b);
  }
}

// The shipped guarantees scene (assets/scenes/seed/guarantees.jsonl): its statistics say what the commands certify, and
// it is deterministic: two replays, and undoing every command then redoing them, give bit-identical meshes.
TEST(Determinism, GuaranteesSceneCertifiesAndReplaysBitForBit) {
  const fs::path log = fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "scenes" / "seed" / "guarantees.jsonl";
  core::Scene a, b;
  editor::History ha(a), hb(b);
  const editor::ReplayResult r = editor::replay_lines(ha, log);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_TRUE(editor::replay_lines(hb, log).ok);
  expect_same_meshes(a, b);

  std::vector<nlohmann::json> certify, refine, press;
  for (const editor::ExecutionRecord& e : r.records) {
    if (e.cmd == "lattice.certify") certify.push_back(e.stats);
    if (e.cmd == "mesh.refine") refine.push_back(e.stats);
    if (e.cmd == "lattice.press") press.push_back(e.stats);
  }
  ASSERT_EQ(certify.size(), 2u);
  ASSERT_EQ(refine.size(), 2u);
  ASSERT_EQ(press.size(), 1u);
  for (const auto& c : certify) EXPECT_EQ(c.at("certificate"), "fold_free") << c.dump();
  for (const auto& f : refine) {
    EXPECT_EQ(f.at("stopped_by"), "converged") << f.dump();
    EXPECT_LE(f.at("max_bound").get<double>(), f.at("tolerance").get<double>()) << f.dump();
    EXPECT_GT(f.at("triangles_after").get<std::size_t>(), f.at("triangles_before").get<std::size_t>()) << f.dump();
  }
  EXPECT_TRUE(press[0].at("limited").get<bool>()) << "the asked strength would fold the lattice";
  EXPECT_GT(press[0].at("strength_used").get<double>(), 0.0);
  EXPECT_LT(press[0].at("strength_used").get<double>(), 0.6);

  const core::Scene after = a;
  const std::size_t applied = ha.applied();
  for (std::size_t i = 0; i < applied; ++i) ha.undo();
  EXPECT_TRUE(a.objects().empty());
  for (std::size_t i = 0; i < applied; ++i) ha.redo();
  expect_same_meshes(a, after);
}

}  // namespace
