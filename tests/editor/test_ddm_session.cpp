// The DDM workflow end to end: tests/logs/ddm_session.jsonl paints thorns onto the teapot, hexagons onto the
// Venus bust and chain links onto the bunny, animates the thorns into flowers, records frames 20–24 and bakes all
// three layers; `replay` runs it headless, the baked objects are the layers' CPU reference meshes (the thorns at
// frame 24), scene.glb holds baked and live layers, and a second replay writes the same scene.glb byte for byte.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/ddm/ddm_layer.h"
#include "core/mesh/gltf_anim_io.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

const fs::path kLog = fs::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs" / "ddm_session.jsonl";

fs::path replay_into(const std::string& name) {
  const fs::path out = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / name;
  fs::remove_all(out);
  editor::ReplayOptions opt;
  opt.log = kLog;
  opt.out_dir = out;
  opt.render = false;  // anim.record still renders its frames (GL through EGL)
  EXPECT_EQ(editor::run_replay(opt), 0);
  return out;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(DdmSession, PaintAnimateRecordAndBakeReplayHeadless) {
  const fs::path out = replay_into("ddm_session");
  std::ifstream rin(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(rin);
  ASSERT_TRUE(report.at("ok").get<bool>()) << report.dump();
  int strokes = 0;
  for (const auto& c : report.at("commands"))
    if (c.at("cmd") == "ddm.paint") {
      ++strokes;
      EXPECT_GT(c.at("stats").at("cells_added").get<int>(), 0) << c.dump();
    }
  EXPECT_EQ(strokes, 4);

  // The recording: five frames and animation.glb with the thorn layer as a morph-animated node.
  EXPECT_EQ(report.at("record").at("frames_written"), 5);
  for (int f = 20; f <= 24; ++f) EXPECT_TRUE(fs::exists(out / ("frame_00" + std::to_string(f) + ".png"))) << f;
  const core::MorphAnimationInfo anim = core::read_morph_animation_info(out / "animation.glb");
  bool thorns_animated = false;
  for (const auto& m : anim.meshes) thorns_animated |= m.name == "pot/thorns" && m.targets == 4;
  EXPECT_TRUE(thorns_animated);

  // The same session in memory: each baked object is its layer's CPU reference mesh in world units.
  core::Scene scene;
  editor::History history(scene);
  ASSERT_TRUE(editor::replay_lines(history, kLog).ok);
  const double t24 = scene.timeline.time_of_frame(24);
  for (const auto& [object, layer_name, baked, time_s] :
       std::vector<std::tuple<std::string, std::string, std::string, double>>{
           {"pot", "thorns", "pot.thorns", t24},
           {"bust", "hexes", "bust.hexes", 0.0},
           {"bunny", "chains", "bunny.chains", 0.0}}) {
    const core::SceneObject& owner = *scene.find(object);
    ASSERT_EQ(owner.ddm_layers.size(), 1u) << object;
    const core::DdmLayer& layer = *owner.ddm_layers.front();
    EXPECT_EQ(layer.name, layer_name);
    const core::TriMesh expected = core::transformed(core::ddm_layer_mesh(layer, time_s), owner.transform);
    const core::SceneObject* b = scene.find(baked);
    ASSERT_NE(b, nullptr) << baked;
    ASSERT_EQ(b->world_mesh->vertex_count(), expected.vertex_count()) << baked;
    ASSERT_EQ(expected.vertex_count(), layer.instances.size() * layer.tiles.at(0).mesh.vertex_count()) << baked;
    for (std::size_t v = 0; v < expected.vertex_count(); ++v)
      ASSERT_EQ(b->world_mesh->positions[v], expected.positions[v]) << baked << " v" << v;
  }
  // The thorns were baked opened: frame 24 (α = 1, flowers) is not the layer at time 0 (thorns).
  const core::TriMesh thorns = *scene.find("pot")->ddm_layers.front()->mesh;
  const core::TriMesh flowers = core::ddm_layer_mesh(*scene.find("pot")->ddm_layers.front(), t24);
  double opened = 0.0;
  for (std::size_t v = 0; v < thorns.vertex_count(); ++v)
    opened = std::max(opened, glm::length(thorns.positions[v] - flowers.positions[v]));
  EXPECT_GT(opened, 0.01);

  // scene.glb: every object, baked layers as objects and live layers as "<object>/<layer>" nodes.
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (out / "scene.glb").string())) << err;
  std::map<std::string, std::size_t> vertices;
  for (const auto& node : model.nodes)
    if (node.mesh >= 0)
      vertices[node.name] =
          model.accessors.at(model.meshes[node.mesh].primitives.at(0).attributes.at("POSITION")).count;
  for (const char* name :
       {"pot", "bust", "bunny", "pot.thorns", "bust.hexes", "bunny.chains", "pot/thorns", "bust/hexes", "bunny/chains"})
    EXPECT_TRUE(vertices.count(name)) << name;
  EXPECT_EQ(vertices["bust.hexes"], vertices["bust/hexes"]);
  EXPECT_EQ(vertices["bunny.chains"], scene.find("bunny.chains")->world_mesh->vertex_count());

  // Determinism: the same log gives the same scene.glb, byte for byte.
  const fs::path again = replay_into("ddm_session_again");
  EXPECT_TRUE(bytes(out / "scene.glb") == bytes(again / "scene.glb"));
}

}  // namespace
