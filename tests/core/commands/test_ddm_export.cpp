// ddm.export (core/commands/ddm_export.h, core/ddm/ddm_map_image.h; seed Figs. 5.3, 5.5): a tile layer's sampled P and
// N maps written as PNG pictures — one pixel per sample with v upwards, normals decoding to unit vectors, positions
// spanning their box — inside the output folder only, the scene unchanged, and nothing written for a refused line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/commands/ddm_export.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/scene_primitive.h"
#include "core/ddm/ddm_map_image.h"
#include "core/image/image_io.h"
#include "tests/core/commands/command_test_util.h"

namespace trispline::core {
namespace ddm_export_test {

using nlohmann::json;
namespace fs = std::filesystem;

struct TeapotLayer {
  Scene scene;
  CommandContext ctx;
  TeapotLayer() {
    ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"teapot","name":"pot"})"), {})
        ->redo(scene);
    DdmFillCommand::parse(json::parse(R"({"cmd":"ddm.fill","object":"pot","layer":"thorns","tile":"thorn",
        "layout":"rect","counts":[6,3],"height":0.1,"base":"teapot_body","map_resolution":[65,33]})"),
                          {})
        ->redo(scene);
    ctx.output_dir = fs::path(testing::TempDir()) / "ddm_export";
    fs::remove_all(ctx.output_dir);
    fs::create_directories(ctx.output_dir);
  }
  CommandPtr run(const std::string& what, const std::string& path) {
    CommandPtr c = DdmExportCommand::parse(
        json{{"cmd", "ddm.export"}, {"object", "pot"}, {"layer", "thorns"}, {"what", what}, {"path", path}}, ctx);
    c->redo(scene);
    return c;
  }
};

TEST(DdmExport, TeapotBodyMapsArePicturesOfPAndN) {
  TeapotLayer t;
  const std::shared_ptr<const DdmLayer> layer = t.scene.find("pot")->ddm_layers.at(0);
  const DdmMaps& maps = *layer->maps;
  ASSERT_EQ(maps.slot_count(), 1);
  const CommandPtr p = t.run("positions", "maps/pot_P.png");
  const CommandPtr n = t.run("normals", "maps/pot_N.png");
  EXPECT_EQ(t.scene.find("pot")->ddm_layers.at(0), layer) << "the scene does not change";
  EXPECT_EQ(p->stats()["width"], 65);
  EXPECT_EQ(p->stats()["height"], 33);

  const ImageRgba8 pi = read_image_rgba8(t.ctx.output_dir / "maps/pot_P.png");
  const ImageRgba8 ni = read_image_rgba8(t.ctx.output_dir / "maps/pot_N.png");
  ASSERT_EQ(pi.width, 65);
  ASSERT_EQ(pi.height, 33);
  ASSERT_EQ(ni.width, 65);
  ASSERT_EQ(ni.height, 33);
  int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
  double worst_unit = 0.0, worst_sample = 0.0;
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 65; ++i) {
      const std::size_t px = (static_cast<std::size_t>(32 - j) * 65 + i) * 4;  // v upwards: sample row j from below
      const float* f = maps.sample(0, i, j);
      glm::dvec3 dn;
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min<int>(lo[c], pi.rgba[px + c]), hi[c] = std::max<int>(hi[c], pi.rgba[px + c]);
        dn[c] = 2.0 * ni.rgba[px + c] / 255.0 - 1.0;
      }
      EXPECT_EQ(pi.rgba[px + 3], 255);  // a patch base: every sample lies on the surface
      worst_unit = std::max(worst_unit, std::abs(glm::length(dn) - 1.0));
      worst_sample = std::max(worst_sample, glm::length(dn - glm::dvec3(f[3], f[4], f[5])));
    }
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(lo[c], 0) << "channel " << c << " spans the positions' box";
    EXPECT_EQ(hi[c], 255) << "channel " << c;
  }
  EXPECT_LT(worst_unit, 0.02) << "8-bit normals decode to unit vectors";
  EXPECT_LT(worst_sample, 0.01) << "each pixel is its sample's normal";
}

TEST(DdmExport, RefusedLinesWriteNothingAndBlameTheirField) {
  TeapotLayer t;
  EXPECT_TRUE(test::throws_command_error([&] { t.run("normals", "../outside.png"); }, "path", "outside"));
  EXPECT_TRUE(test::throws_command_error([&] { t.run("normals", "n.jpg"); }, "path", ".png"));
  EXPECT_TRUE(test::throws_command_error([&] { t.run("depth", "n.png"); }, "what", "positions|normals"));
  EXPECT_TRUE(test::throws_command_error(
      [&] {
        DdmExportCommand::parse(json::parse(R"({"cmd":"ddm.export","object":"pot","layer":"fur","path":"f.png"})"),
                                t.ctx)
            ->redo(t.scene);
      },
      "layer", "fur"));
  EXPECT_TRUE(fs::is_empty(t.ctx.output_dir));
}

TEST(DdmExport, MapImageRefusesOversizedAndInconsistentMaps) {
  const auto message = [](const DdmMaps& maps) -> std::string {
    try {
      ddm_map_image(maps, DdmMapQuantity::normals);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(accepted)";
  };
  DdmMaps maps;
  EXPECT_NE(message(maps).find("no sampled chart"), std::string::npos) << message(maps);
  maps.resolution = {4097, 4097};  // 9 charts: 12,291² pixels, refused before any sample is read or pixel allocated
  maps.chart_of_slot.assign(9, 0);
  maps.slot_of_chart.assign(9, 0);
  EXPECT_NE(message(maps).find("allowed"), std::string::npos) << message(maps);
  maps.resolution = {3, 3};  // small enough, but no samples behind it
  EXPECT_NE(message(maps).find("do not match"), std::string::npos) << message(maps);
}

}  // namespace ddm_export_test
}  // namespace trispline::core
