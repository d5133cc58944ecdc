// Tile layers carried by the commands that deform their objects (tests/logs/ddm_follow.jsonl through the registry
// and the undo history, as a replay runs it): place.sketch, lattice.ring with an animated offset, dffd.split,
// incision.draw with a keyed opening. Each layer moves with its object; replays, stills and undo/redo are bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/scene/ddm_follow.h"
#include "core/scene/scene_export.h"
#include "editor/commands/command_log.h"
#include "tests/core/commands/history_test_util.h"
#include "tests/test_paths.h"

namespace trispline::core {
namespace ddm_follow_commands_test {

void replay(editor::History& history) {
  const CommandContext ctx{test::logs_dir(), {}};
  for (const editor::LogLine& l : editor::read_log(test::log_path("ddm_follow.jsonl")))
    history.execute(editor::CommandRegistry::builtin().parse(l.json, ctx));
}

// Every exported mesh of the scene at `t`, positions and normals as bytes.
std::vector<std::string> exported(const Scene& scene, double t) {
  const Scene still = scene_at_time(scene, t);
  const SceneExport ex = scene_export_nodes(still);
  std::vector<std::string> out;
  for (const GltfNode& n : ex.nodes) {
    if (!n.mesh) continue;
    std::string b(reinterpret_cast<const char*>(n.mesh->positions.data()), n.mesh->positions.size() * 24);
    b.append(reinterpret_cast<const char*>(n.mesh->normals.data()), n.mesh->normals.size() * 24);
    out.push_back(n.name + ":" + b);
  }
  return out;
}

TEST(DdmFollowCommands, EveryDeformationCarriesItsLayer) {
  Scene scene;
  editor::History history(scene);
  ASSERT_NO_THROW(replay(history));
  for (const char* name : {"cut", "ring", "split", "rug"}) {
    const SceneObject& o = *scene.find(name);
    ASSERT_EQ(o.ddm_layers.size(), 1u) << name;
    const DdmLayer& layer = *o.ddm_layers.front();
    const DdmLayerDeformation d(o, layer, 0.5);
    EXPECT_FALSE(d.rigid()) << name;
    const TriMesh carried = d.apply(*layer.mesh), plain = transformed(*layer.mesh, o.transform);
    double moved = 0.0;
    for (std::size_t v = 0; v < carried.positions.size(); ++v) {
      ASSERT_TRUE(std::isfinite(carried.positions[v].x) && std::isfinite(carried.normals[v].x)) << name;
      moved = std::max(moved, glm::length(carried.positions[v] - plain.positions[v]));
    }
    EXPECT_GT(moved, 0.01) << name << ": the tiles did not move with the object";
  }
  EXPECT_TRUE(scene.find("cut")->morph && scene.find("cut")->morph->animated());
  EXPECT_EQ(scene.find("cut")->morph->weight_at(0.0), 0.0);  // frame 1: closed
  // The placed rug's tiles sit inside its lattice box (embedded with the tiles), not clamped flat against it.
  const SceneObject& rug = *scene.find("rug");
  const TriMesh world = transformed(*rug.ddm_layers.front()->mesh, rug.transform);
  for (const glm::dvec3& p : embed_points(rug.ffd->embedding, world.positions))
    ASSERT_TRUE(p.x >= -1e-9 && p.x <= 1 + 1e-9 && p.y >= -1e-9 && p.y <= 1 + 1e-9 && p.z >= -1e-9 && p.z <= 1 + 1e-9);
}

TEST(DdmFollowCommands, ReplayStillsAndUndoRedoAreBitForBit) {
  Scene a, b;
  editor::History ha(a), hb(b);
  replay(ha);
  replay(hb);
  for (const double t : {0.0, 0.37, 0.9}) EXPECT_EQ(exported(a, t), exported(b, t)) << "t = " << t;
  const std::vector<std::string> before = exported(a, 0.37);
  std::size_t steps = 0;
  while (ha.can_undo()) ha.undo(), ++steps;
  EXPECT_TRUE(a.objects().empty());
  for (std::size_t i = 0; i < steps; ++i) ha.redo();
  EXPECT_EQ(exported(a, 0.37), before);
}

}  // namespace ddm_follow_commands_test
}  // namespace trispline::core
