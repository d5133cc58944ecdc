// ddm.animate (core/commands/ddm_animate.h; seed §5.4.2, Eq. 5.3): metamorphosis keys, texture-space offset, keyed
// rotation, scale and w on a layer, the scene at any time (scene_at_time) equal to the layer evaluated there, undo, bad
// input refused with the scene unchanged, the log line round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/commands/ddm_animate.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/scene_primitive.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace ddm_animate_test {

using nlohmann::json;

Scene pot_with_thorns() {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})->redo(s);
  DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","object":"pot","layer":"t","tile":"thorn","layout":"rect",
      "counts":[8,2],"height":0.05,"base":"teapot_body","map_resolution":[65,33]})"),
                        {})
      ->redo(s);
  return s;
}

TEST(DdmAnimate, MorphAndOffsetPlayOverTimeAndUndo) {
  Scene s = pot_with_thorns();
  const auto before = s.find("pot")->ddm_layers.at(0);
  auto cmd = DdmAnimateCommand::parse(json::parse(R"({"cmd":"ddm.animate","object":"pot","layer":"t",
      "morph_tile":"flower","alpha_keys":[[1,0],[25,1]],"offset_keys":[[1,0,0],[25,0.25,0]]})"),
                                      {});
  cmd->redo(s);
  const DdmLayer& layer = *s.find("pot")->ddm_layers.at(0);
  ASSERT_TRUE(layer.animated());
  EXPECT_EQ(layer.alpha_keys.size(), 2u);
  EXPECT_DOUBLE_EQ(layer.alpha_at(0.5), 0.5);  // frame 13 of 24 fps
  EXPECT_DOUBLE_EQ(layer.offset_at(1.0).x, 0.25);
  EXPECT_EQ(layer.mesh->positions, before->mesh->positions);  // α = 0 and no offset at time 0
  // The scene at 1 s: the layer is a still whose mesh is the layer evaluated there (flowers moved 2 cells round).
  const Scene later = scene_at_time(s, 1.0);
  const DdmLayer& still = *later.find("pot")->ddm_layers.at(0);
  EXPECT_FALSE(still.animated());
  EXPECT_DOUBLE_EQ(still.alpha, 1.0);
  EXPECT_EQ(still.mesh->positions, ddm_layer_mesh(layer, 1.0).positions);
  EXPECT_EQ(still.mesh->positions, ddm_layer_mesh(still, 0.0).positions);  // a still shows the same at any time
  double moved = 0.0;
  for (std::size_t v = 0; v < still.mesh->vertex_count(); ++v)
    moved = std::max(moved, glm::length(still.mesh->positions[v] - layer.mesh->positions[v]));
  EXPECT_GT(moved, 0.1);
  // Round trip of the log line, then undo.
  EXPECT_EQ(DdmAnimateCommand::parse(cmd->to_json(), {})->to_json(), cmd->to_json());
  cmd->undo(s);
  EXPECT_EQ(s.find("pot")->ddm_layers.at(0), before);
}

// Articulated tiles (seed Fig. 5.13): ddm.fill with tile_clip makes an animated layer whose tile is the glTF figure
// posed at each time; the scene at a time freezes that pose into a still; the line round-trips; a morph partner is
// refused; undo removes the layer.
TEST(DdmAnimate, ArticulatedTilesPlayTheirClipAndFreezeInStills) {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})->redo(s);
  CommandContext ctx;
  ctx.base_dir = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets" / "data";
  auto fill = DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","object":"pot","layer":"robots",
      "tile":"qt3d/gltf/2.0/RiggedFigure/RiggedFigure.gltf","tile_up":"y","tile_clip":"*","layout":"rect",
      "counts":[8,2],"height":0.1,"base":"teapot_body","map_resolution":[65,33]})"),
                                    ctx);
  fill->redo(s);
  const DdmLayer& layer = *s.find("pot")->ddm_layers.at(0);
  ASSERT_TRUE(layer.tile_clip);
  ASSERT_TRUE(layer.animated());
  EXPECT_EQ(layer.tiles.at(0).mesh.vertex_count(), 370u);
  // The tile stands on y: its w extent is its height, larger than its depth across the cell.
  Aabb box;
  for (const glm::dvec3& p : layer.tiles[0].mesh.positions) box.extend(p);
  EXPECT_GT(box.size().z, 0.9);
  const TriMesh at0 = ddm_layer_mesh(layer, 0.0), at06 = ddm_layer_mesh(layer, 0.6);
  EXPECT_EQ(at0.positions, layer.mesh->positions);
  double moved = 0.0;
  for (std::size_t v = 0; v < at0.vertex_count(); ++v)
    moved = std::max(moved, glm::length(at06.positions[v] - at0.positions[v]));
  EXPECT_GT(moved, 1e-3) << "the figures move";
  const Scene later = scene_at_time(s, 0.6);
  const DdmLayer& still = *later.find("pot")->ddm_layers.at(0);
  EXPECT_FALSE(still.animated());
  EXPECT_EQ(still.mesh->positions, at06.positions);
  EXPECT_EQ(ddm_layer_mesh(still, 0.0).positions, at06.positions);  // the pose is frozen
  EXPECT_EQ(DdmFillCommand::parse(fill->to_json(), ctx)->to_json(), fill->to_json());
  try {
    DdmAnimateCommand::parse(json::parse(R"({"cmd":"ddm.animate","object":"pot","layer":"robots",
        "morph_tile":"thorn"})"),
                             {})
        ->redo(s);
    ADD_FAILURE() << "a morph partner of an articulated tile was accepted";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "morph_tile");
  }
  fill->undo(s);
  EXPECT_TRUE(s.find("pot")->ddm_layers.empty());
}

// Keyed rotation, scale and w are the layer's own transform and height moved over time: at 1 s the keyed layer is,
// bit for bit, the same layer with rotate_deg + 90, scale × 0.5 and height × 2 set once.
TEST(DdmAnimate, RotationScaleAndWKeysMoveTheLayersTransform) {
  Scene s = pot_with_thorns();
  const auto before = s.find("pot")->ddm_layers.at(0);
  auto cmd = DdmAnimateCommand::parse(json::parse(R"({"cmd":"ddm.animate","object":"pot","layer":"t",
      "rotate_keys":[[1,0],[25,90]],"scale_keys":[[1,1],[25,0.5]],"w_keys":[[1,1],[25,2]]})"),
                                      {});
  cmd->redo(s);
  const DdmLayer& layer = *s.find("pot")->ddm_layers.at(0);
  ASSERT_TRUE(layer.animated());
  EXPECT_EQ(layer.mesh->positions, before->mesh->positions);   // the keys start at the layer's own transform
  EXPECT_DOUBLE_EQ(layer.transform_at(0.5).rotate_deg, 45.0);  // frame 13 of 24 fps, linear
  EXPECT_DOUBLE_EQ(layer.transform_at(1.0).scale.x, 0.5);
  EXPECT_DOUBLE_EQ(layer.height_at(1.0), 0.1);
  DdmLayer set_once = *before;
  set_once.transform.rotate_deg += 90.0, set_once.transform.scale *= 0.5, set_once.height *= 2.0;
  const TriMesh keyed = ddm_layer_mesh(layer, 1.0);
  EXPECT_EQ(keyed.positions, ddm_layer_mesh(set_once, 0.0).positions);
  EXPECT_EQ(keyed.normals, ddm_layer_mesh(set_once, 0.0).normals);
  // Tiles taller by w: the farthest tile vertex from the pot's axis moves out.
  auto reach = [](const TriMesh& m) {
    double r = 0.0;
    for (const glm::dvec3& p : m.positions) r = std::max(r, std::hypot(p.x, p.z));
    return r;
  };
  EXPECT_GT(reach(keyed), reach(*layer.mesh) + 0.02);
  // The scene at 1 s holds a still of that pose.
  const Scene later = scene_at_time(s, 1.0);
  const DdmLayer& still = *later.find("pot")->ddm_layers.at(0);
  EXPECT_FALSE(still.animated());
  EXPECT_EQ(still.mesh->positions, keyed.positions);
  EXPECT_EQ(ddm_layer_mesh(still, 3.0).positions, keyed.positions);
  // Round trip, clear, undo.
  EXPECT_EQ(DdmAnimateCommand::parse(cmd->to_json(), {})->to_json(), cmd->to_json());
  auto clear =
      DdmAnimateCommand::parse(json::parse(R"({"cmd":"ddm.animate","object":"pot","layer":"t","clear":true})"), {});
  clear->redo(s);
  EXPECT_FALSE(s.find("pot")->ddm_layers.at(0)->animated());
  EXPECT_EQ(s.find("pot")->ddm_layers.at(0)->mesh->positions, before->mesh->positions);
  clear->undo(s);
  cmd->undo(s);
  EXPECT_EQ(s.find("pot")->ddm_layers.at(0), before);
}

TEST(DdmAnimate, BadInputIsRefusedAndTheSceneIsUnchanged) {
  Scene s = pot_with_thorns();
  const auto before = s.find("pot")->ddm_layers.at(0);
  auto field_of = [&](const char* line) {
    return trispline::test::command_field_of<DdmAnimateCommand>(s, json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tile":"chain"})"), "morph_tile");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tiles":[]})"), "morph_tiles");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tiles":["flower",""]})"), "morph_tiles");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","alpha_keys":[[1,0],[9,1]]})"), "alpha_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tile":"flower",
      "alpha_keys":[[1,0],[1,1]]})"),
            "alpha_keys");  // two keys on one frame
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","offset_keys":[[1,0]]})"), "offset_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","scale_keys":[[1,1],[9,0]]})"), "scale_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","w_keys":[[1,-1]]})"), "w_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","rotate_keys":[[1,1e9]]})"), "rotate_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","rotate_keys":[[3,0],[3,9]]})"),
            "rotate_keys");  // two keys on one frame
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","w_keys":[[1,"x"]]})"), "w_keys");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"nope","alpha":0.5})"), "layer");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"nope","layer":"t"})"), "object");
  EXPECT_EQ(s.find("pot")->ddm_layers.at(0), before);
  // α outside [0, 1] extrapolates (Eq. 5.3 allows it).
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tile":"flower","alpha":1.5})"),
            "(accepted)");
  EXPECT_DOUBLE_EQ(s.find("pot")->ddm_layers.at(0)->alpha_at(3.0), 1.5);
  // "morph_tile":"" removes the morph (the Tile Paint tool's "(none)").
  EXPECT_EQ(field_of(R"({"cmd":"ddm.animate","object":"pot","layer":"t","morph_tile":"","alpha":0})"), "(accepted)");
  EXPECT_TRUE(s.find("pot")->ddm_layers.at(0)->morph_tiles.empty());
}

}  // namespace ddm_animate_test
}  // namespace trispline::core
