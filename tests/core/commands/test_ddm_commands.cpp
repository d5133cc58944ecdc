// ddm.fill / ddm.bake (core/commands/ddm_fill.h, ddm_bake.h; seed ch. 5): a layer over a coarse sphere's limit surface
// and over the teapot's body patches, the baked object (world units, instances contiguous in the tile's vertex order),
// undo bit for bit, bad input refused with the scene unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_paint.h"
#include "core/commands/ddm_remove.h"
#include "core/commands/mesh_subdivide.h"
#include "core/commands/scene_primitive.h"
#include "core/scene/primitives.h"
#include "core/scene/scene_export.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace ddm_commands_test {

using nlohmann::json;

Scene ball_scene() {
  Scene s;
  s.insert(trispline::test::sphere_object("ball", 8, 4, {2.0, 0.0, 0.0}));
  return s;
}

TEST(DdmCommands, FillThenBakeOnALimitSurface) {
  Scene s = ball_scene();
  const TriMesh rest = *s.find("ball")->rest_mesh;
  auto fill = DdmFillCommand::parse(
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"spikes","tile":"thorn",
      "layout":"rect","counts":[1,1],"height":0.2})"),
      {});
  EXPECT_EQ(fill->to_json()["counts"], json::parse("[1,1]"));
  fill->redo(s);
  const SceneObject& ball = *s.find("ball");
  ASSERT_EQ(ball.ddm_layers.size(), 1u);
  const DdmLayer& layer = *ball.ddm_layers[0];
  EXPECT_EQ(layer.instances.size(), 3 * rest.triangle_count());  // one tile per chart, three charts per face
  EXPECT_EQ(layer.mesh->vertex_count(), layer.instances.size() * 626);
  EXPECT_EQ(fill->stats()["tiles"], layer.instances.size());
  // The limit surface of this coarse sphere lies inside its unit-sphere vertices; thorn tips stand 0.9·0.2 above it.
  double far = 0.0;
  for (const glm::dvec3& p : layer.mesh->positions) far = std::max(far, glm::length(p));
  EXPECT_GT(far, 1.0);
  EXPECT_LT(far, 1.18);

  auto bake = DdmBakeCommand::parse(json::parse(R"({"cmd":"ddm.bake","object":"ball","layer":"spikes",
      "name":"spikes.baked"})"),
                                    {});
  bake->redo(s);
  const SceneObject* baked = s.find("spikes.baked");
  ASSERT_TRUE(baked);
  ASSERT_EQ(baked->rest_mesh->vertex_count(), layer.mesh->vertex_count());
  EXPECT_EQ(baked->rest_mesh->triangles, layer.mesh->triangles);
  for (std::size_t v = 0; v < layer.mesh->vertex_count(); v += 101)  // world units: the ball's translation applied
    EXPECT_NEAR(glm::length(baked->world_mesh->positions[v] - (layer.mesh->positions[v] + glm::dvec3(2, 0, 0))), 0.0,
                1e-12);
  bake->undo(s);
  EXPECT_FALSE(s.find("spikes.baked"));
  fill->undo(s);
  EXPECT_TRUE(s.find("ball")->ddm_layers.empty());
  EXPECT_EQ(s.find("ball")->rest_mesh->positions, rest.positions);
}

TEST(DdmCommands, ALayersOwnColourIsDrawnBakedAndExported) {
  Scene s = ball_scene();
  auto fill =
      DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"gold","tile":"hex",
      "layout":"rect","counts":[1,1],"height":0.05,"color":[0.9,0.6,0.1]})"),
                            {});
  EXPECT_EQ(fill->to_json()["color"].size(), 3u);  // logged back
  fill->redo(s);
  const glm::vec3 gold(0.9f, 0.6f, 0.1f);
  ASSERT_TRUE(s.find("ball")->ddm_layers.at(0)->color.has_value());
  EXPECT_EQ(*s.find("ball")->ddm_layers.at(0)->color, gold);
  DdmBakeCommand::parse(json::parse(R"({"cmd":"ddm.bake","object":"ball","layer":"gold","name":"g"})"), {})->redo(s);
  EXPECT_EQ(s.find("g")->color, gold);
  const SceneExport nodes = scene_export_nodes(s);
  bool exported = false;
  for (const auto& n : nodes.nodes)
    if (n.name == "ball/gold") exported = n.color == gold;
  EXPECT_TRUE(exported);
  // ddm.color recolours the layer alone (tiles, maps and mesh shared); null gives it the object's again; undo.
  const auto before = s.find("ball")->ddm_layers.at(0);
  auto blue = DdmColorCommand::parse(json::parse(R"({"cmd":"ddm.color","object":"ball","layer":"gold",
      "color":[0.1,0.2,0.9]})"),
                                     {});
  blue->redo(s);
  const auto after = s.find("ball")->ddm_layers.at(0);
  EXPECT_EQ(*after->color, glm::vec3(0.1f, 0.2f, 0.9f));
  EXPECT_EQ(after->mesh, before->mesh);
  EXPECT_EQ(after->maps, before->maps);
  blue->undo(s);
  EXPECT_EQ(s.find("ball")->ddm_layers.at(0), before);
  auto clear = DdmColorCommand::parse(json::parse(R"({"cmd":"ddm.color","object":"ball","layer":"gold",
      "color":null})"),
                                      {});
  EXPECT_TRUE(clear->to_json()["color"].is_null());
  clear->redo(s);
  EXPECT_FALSE(s.find("ball")->ddm_layers.at(0)->color.has_value());
  clear->undo(s);
  EXPECT_THROW(DdmColorCommand::parse(json::parse(R"({"cmd":"ddm.color","object":"ball","layer":"gold",
      "color":[2,0,0]})"),
                                      {}),
               CommandError);
  EXPECT_THROW(DdmColorCommand::parse(json::parse(R"({"cmd":"ddm.color","object":"ball","layer":"gold"})"), {}),
               CommandError);
  EXPECT_THROW(DdmColorCommand::parse(json::parse(R"({"cmd":"ddm.color","object":"ball","layer":"nope",
      "color":null})"),
                                      {})
                   ->redo(s),
               CommandError);
  // Without "color" the layer takes the object's colour everywhere.
  DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"plain","tile":"hex",
      "layout":"rect","counts":[1,1],"height":0.05})"),
                        {})
      ->redo(s);
  EXPECT_FALSE(s.find("ball")->ddm_layers.at(1)->color.has_value());
  DdmBakeCommand::parse(json::parse(R"({"cmd":"ddm.bake","object":"ball","layer":"plain","name":"p"})"), {})->redo(s);
  EXPECT_EQ(s.find("p")->color, s.find("ball")->color);
}

TEST(DdmCommands, RemoveALayerAndCommandsThatWouldLeaveTilesBehindAreRefused) {
  Scene s = ball_scene();
  DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"spots","tile":"hex",
      "layout":"rect","counts":[1,1],"height":0.05})"),
                        {})
      ->redo(s);
  const auto layer = s.find("ball")->ddm_layers.at(0);
  // A new mesh would leave the tiles on the old surface: refused, naming the layer; the object is unchanged.
  auto subdivide = MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"ball"})"), {});
  try {
    subdivide->redo(s);
    ADD_FAILURE() << "mesh.subdivide accepted an object with tile layers";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "object");
    EXPECT_NE(std::string(e.what()).find("tile layers (spots)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ddm.remove"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.find("ball")->ddm_layers.at(0), layer);
  // ddm.remove deletes it; undo brings back the very layer; then the mesh may change.
  auto remove = DdmRemoveCommand::parse(json::parse(R"({"cmd":"ddm.remove","object":"ball","layer":"spots"})"), {});
  EXPECT_EQ(remove->to_json(), json::parse(R"({"cmd":"ddm.remove","object":"ball","layer":"spots"})"));
  remove->redo(s);
  EXPECT_TRUE(s.find("ball")->ddm_layers.empty());
  EXPECT_EQ(remove->stats()["tiles"], layer->instances.size());
  remove->undo(s);
  ASSERT_EQ(s.find("ball")->ddm_layers.size(), 1u);
  EXPECT_EQ(s.find("ball")->ddm_layers.at(0), layer);
  remove->redo(s);
  EXPECT_NO_THROW(MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"ball"})"), {})->redo(s));
  auto again = DdmRemoveCommand::parse(json::parse(R"({"cmd":"ddm.remove","object":"ball","layer":"spots"})"), {});
  EXPECT_THROW(again->redo(s), CommandError);
}

TEST(DdmCommands, TeapotBodyLayerAndReplacingALayer) {
  Scene s;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})->redo(s);
  auto fill = [&](const char* line) { DdmFillCommand::parse(json::parse(line), {})->redo(s); };
  fill(R"({"cmd":"ddm.fill","object":"pot","layer":"a","tile":"hex","layout":"hex","counts":[24,10],"height":0.02,
          "base":"teapot_body"})");
  const SceneObject& pot = *s.find("pot");
  ASSERT_EQ(pot.ddm_layers.size(), 1u);
  EXPECT_EQ(pot.ddm_layers[0]->instances.size(), 5u * 24 + 5u * 23);  // one chart: the 8 patches, round the pot
  EXPECT_EQ(pot.ddm_layers[0]->maps->slot_count(), 1);
  fill(R"({"cmd":"ddm.fill","object":"pot","layer":"a","tile":"thorn","layout":"rect","counts":[2,2],"height":0.05,
          "base":"teapot_body"})");
  ASSERT_EQ(s.find("pot")->ddm_layers.size(), 1u);  // same name: replaced
  EXPECT_EQ(s.find("pot")->ddm_layers[0]->tile_sources.at(0), "thorn");
  EXPECT_EQ(s.find("pot")->ddm_layers[0]->instances.size(), 4u);
}

// A tile from a mesh file, relative to the log's folder: made canonical, logged with its absolute path.
TEST(DdmCommands, TileFromAFileRelativeToTheLog) {
  CommandContext ctx;
  ctx.base_dir = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "tests" / "logs";
  auto fill = DdmFillCommand::parse(
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"t","tile":"data/brick.obj",
      "layout":"rect","counts":[1,1],"height":0.1})"),
      ctx);
  EXPECT_TRUE(std::filesystem::path(fill->to_json().at("tile").get<std::string>()).is_absolute());
  Scene s = ball_scene();
  fill->redo(s);
  const DdmLayer& layer = *s.find("ball")->ddm_layers.at(0);
  EXPECT_EQ(layer.tiles.at(0).name, "brick");
  EXPECT_NEAR(layer.tiles.at(0).mesh.positions[6].z, 0.25, 1e-12);  // z extent 0.5 over the larger span 2
  Aabb b;
  for (const glm::dvec3& p : layer.tiles.at(0).mesh.positions) b.extend(p);
  EXPECT_NEAR(b.hi.x, 1.0, 1e-12);
  EXPECT_NEAR(b.hi.y, 1.0, 1e-12);
}

TEST(DdmCommands, BadInputIsRefusedAndTheSceneIsUnchanged) {
  auto field_of = [](const char* line, Scene& s) {
    return trispline::test::command_field_of<DdmFillCommand>(s, json::parse(line));
  };
  Scene s = ball_scene();
  EXPECT_EQ(
      field_of(
          R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect","counts":[0,2],
      "height":0.1})",
          s),
      "counts");
  EXPECT_EQ(
      field_of(
          R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect","counts":[1,1],
      "height":0})",
          s),
      "height");
  EXPECT_EQ(
      field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"spiral.obj","layout":"rect",
      "counts":[1,1],"height":0.1})",
               s),
      "tile");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"zigzag",
      "counts":[1,1],"height":0.1})",
                     s),
            "layout");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"nope","layer":"x","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.1})",
                     s),
            "object");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","object":"ball","layer":"x","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.1,"base":"teapot_body"})",
                     s),
            "base");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect",
      "counts":[400,400],"height":0.1})",
                     s),
            "counts");  // too many tile vertices
  // Counts that would make 10¹⁰ cells are refused from the numbers, before a cell is made (once a bare bad_alloc).
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"hex",
      "counts":[100000,100000],"height":0.1})",
                     s),
            "counts");
  // A tile size far below the ball is the most tiles, not the fewest (5e-324 once laid one tile per chart).
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect",
      "tile_size":5e-324,"height":0.1})",
                     s),
            "tile_size");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","object":"ball","layer":"x","tile":"thorn","layout":"rect",
      "base":"auto_uv","tile_size":1e-300,"height":0.1})",
                     s),
            "tile_size");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"x","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.1,"color":[0.5,1.5,0]})",
                     s),
            "color");
  // A non-manifold base.
  SceneObject fin;
  fin.name = "fin";
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  fin.rest_mesh = std::make_shared<const TriMesh>(m);
  fin.refresh();
  s.insert(fin);
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","base":"limit","object":"fin","layer":"x","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.1})",
                     s),
            "base");
  EXPECT_EQ(field_of(R"({"cmd":"ddm.fill","object":"fin","layer":"x","tile":"thorn","layout":"rect",
      "counts":[1,1],"height":0.1,"base":"uv"})",
                     s),
            "base");  // no texture coordinates
  for (const SceneObject& o : s.objects()) EXPECT_TRUE(o.ddm_layers.empty()) << o.name;
  // Bake: unknown layer, taken name.
  DdmFillCommand::parse(
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"ok","tile":"hex","layout":"rect",
      "counts":[1,1],"height":0.1})"),
      {})
      ->redo(s);
  auto bake_field = [&](const char* line) {
    return trispline::test::command_field_of<DdmBakeCommand>(s, json::parse(line));
  };
  EXPECT_EQ(bake_field(R"({"cmd":"ddm.bake","object":"ball","layer":"missing","name":"b"})"), "layer");
  EXPECT_EQ(bake_field(R"({"cmd":"ddm.bake","object":"ball","layer":"ok","name":"fin"})"), "name");
  EXPECT_EQ(s.objects().size(), 2u);
}

}  // namespace ddm_commands_test
}  // namespace trispline::core

namespace trispline::core {
namespace ddm_commands_test {

// The layer fields are declared once (ddm_layer_schema) and written back as the lines had them: several tiles bring
// choice (and a non-zero seed), tile files are resolved against the log's folder, defaults stay out of the line;
// ddm.paint logs them only when the line named one of them.
TEST(DdmCommands, LayerFieldsAreWrittenBackAsDeclared) {
  CommandContext ctx;
  ctx.base_dir = "/logs";
  const json fill =
      json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"t","tile":"thorn","tiles":["m.obj"],
      "seed":7,"layout":"brick","counts":[4,2],"height":0.5,"map_resolution":9.0,"tile_scale":2,"tile_shift":[0,0]})");
  EXPECT_EQ(DdmFillCommand::parse(fill, ctx)->to_json(),
            json::parse(R"({"cmd":"ddm.fill","base":"limit","object":"ball","layer":"t",
      "tile":"thorn","tiles":["/logs/m.obj"],"choice":"pattern","seed":7,"layout":"brick","counts":[4,2],
      "height":0.5,"map_resolution":[9,9],"tile_scale":[2.0,2.0]})"));
  json one = fill;
  one.erase("tiles");
  EXPECT_FALSE(DdmFillCommand::parse(one, ctx)->to_json().contains("seed")) << "seed only with several tiles";
  EXPECT_FALSE(DdmFillCommand::parse(one, ctx)->to_json().contains("choice"));
  one["map_resolution"] = 9.5;
  EXPECT_THROW(DdmFillCommand::parse(one, ctx), CommandError);

  const json paint = json::parse(R"({"cmd":"ddm.paint","object":"ball","layer":"t","stroke":[[1,2]],"radius_px":3})");
  EXPECT_EQ(DdmPaintCommand::parse(paint, ctx)->to_json(),
            json::parse(R"({"cmd":"ddm.paint","object":"ball","layer":"t","stroke":[[1,2]],"radius_px":3,
                "erase":false})"));
  json named = paint;
  named["color"] = {0.5, 0.25, 1};  // any layer field: the new layer's fields are logged back (counts and tile_size
                                    // only when given: unset, the layer takes counts [1,1])
  EXPECT_EQ(DdmPaintCommand::parse(named, ctx)->to_json(),
            json::parse(R"({"cmd":"ddm.paint","object":"ball","layer":"t","stroke":[[1,2]],"radius_px":3,
                "erase":false,"tile":"thorn","layout":"rect","height":0.1,"color":[0.5,0.25,1]})"));
  named["tile_size"] = 0.25;
  EXPECT_EQ(DdmPaintCommand::parse(named, ctx)->to_json()["tile_size"], 0.25);
}

}  // namespace ddm_commands_test
}  // namespace trispline::core
