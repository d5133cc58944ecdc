// `trispline replay LOG --out DIR` end to end on the default scene: final.png, scene.glb and report.json are
// written, the glb holds every object's current mesh named by its id with the vertex order of the scene.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <filesystem>
#include <fstream>

#include "core/image/image_io.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path default_scene() { return fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "scenes" / "default.jsonl"; }

TEST(ReplayOutputs, DefaultSceneWritesPngGlbAndReport) {
  const fs::path out = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "default_scene";
  fs::remove_all(out);
  editor::ReplayOptions opt;
  opt.log = default_scene();
  opt.out_dir = out;
  opt.width = 640;
  opt.height = 360;
  ASSERT_EQ(editor::run_replay(opt), 0);

  // report.json
  std::ifstream rin(out / "report.json");
  ASSERT_TRUE(rin.good());
  const nlohmann::json report = nlohmann::json::parse(rin);
  EXPECT_TRUE(report.at("ok").get<bool>());
  bool saw_placement = false;
  for (const auto& c : report.at("commands")) {
    EXPECT_TRUE(c.at("ok").get<bool>());
    if (c.at("cmd") == "place.sketch") {
      saw_placement = true;
      EXPECT_GT(c.at("stats").at("rays_hit").get<int>(), 0);
    }
  }
  EXPECT_TRUE(saw_placement);

  // The same scene, replayed in memory, is what the glb must contain.
  core::Scene scene;
  editor::History history(scene);
  ASSERT_TRUE(editor::replay_lines(history, default_scene()).ok);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (out / "scene.glb").string())) << err;
  ASSERT_EQ(model.nodes.size(), scene.objects().size());
  for (std::size_t i = 0; i < scene.objects().size(); ++i) {
    const auto& obj = scene.objects()[i];
    const auto& node = model.nodes[i];
    EXPECT_EQ(node.name, obj.name);
    ASSERT_GE(node.mesh, 0);
    const auto& prim = model.meshes[node.mesh].primitives.at(0);
    const auto& acc = model.accessors.at(prim.attributes.at("POSITION"));
    ASSERT_EQ(acc.count, obj.world_mesh->vertex_count()) << obj.name;
    const auto& view = model.bufferViews.at(acc.bufferView);
    const float* p =
        reinterpret_cast<const float*>(model.buffers.at(view.buffer).data.data() + view.byteOffset + acc.byteOffset);
    const std::size_t stride = view.byteStride ? view.byteStride / sizeof(float) : 3;
    for (std::size_t v = 0; v < acc.count; v += 997)  // vertex order preserved
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(p[v * stride + k], static_cast<float>(obj.world_mesh->positions[v][k])) << obj.name << " v" << v;
  }

  // final.png: the requested size and not a blank image.
  const core::ImageRgba8 image = core::read_image_rgba8(out / "final.png");
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 360);
  const auto& rgba = image.rgba;
  std::size_t distinct = 0;
  for (std::size_t i = 4; i < rgba.size(); i += 4)
    if (rgba[i] != rgba[0] || rgba[i + 1] != rgba[1] || rgba[i + 2] != rgba[2]) ++distinct;
  EXPECT_GT(distinct, rgba.size() / 4 / 10) << "final.png looks blank";
}

TEST(ReplayOutputs, BadLogExitsNonZeroAndReportsTheLine) {
  const fs::path out = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "bad";
  fs::remove_all(out);
  editor::ReplayOptions opt;
  opt.log = fs::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs" / "bad_unknown_command.jsonl";
  opt.out_dir = out;
  opt.render = false;
  EXPECT_NE(editor::run_replay(opt), 0);
  std::ifstream rin(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(rin);
  EXPECT_FALSE(report.at("ok").get<bool>());
  EXPECT_EQ(report.at("failed_line").get<int>(), 2);
}

}  // namespace
