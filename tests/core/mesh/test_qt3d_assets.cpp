// Real textured models the project did not make: Qt 3D's example assets (qt3d5-examples), fetched by the asset script
// into assets/data/qt3d/. Compiled only when they exist at configure time (see CMakeLists.txt), so it never skips.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/mesh/model_load.h"

namespace trispline::core {
namespace {

std::filesystem::path qt3d(const std::string& rel) {
  return std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/qt3d" / rel;
}

// Collada, 16 triangle meshes instanced by its nodes (and 3 line meshes, left out on request), 3 JPEG textures.
TEST(Qt3dAssets, WineRackColladaKeepsMaterialsTexturesAndParts) {
  MeshLoadOptions ignore;
  ignore.ignore_loose = true;
  MeshLoadReport report;
  const LoadedModel m = load_model(qt3d("gltf/wine/wine.dae"), ignore, &report);
  EXPECT_EQ(report.ignored_lines, 3u);
  // Every node's instance of its mesh: `assimp export wine.dae w.obj` (assimp's own node walk) writes 121648
  // triangles; `assimp info` counts 7493 faces once per mesh (3 of them lines), the rack's nodes instance them.
  EXPECT_EQ(report.faces + report.duplicate_faces, 121648u);
  ASSERT_EQ(m.mesh.uvs.size(), m.mesh.vertex_count());
  ASSERT_EQ(m.mesh.face_material.size(), m.mesh.triangle_count());
  ASSERT_TRUE(m.materials);
  EXPECT_GE(m.materials->materials.size(), 5u);
  std::set<std::string> decoded;
  for (const auto& image : m.materials->images) {
    EXPECT_TRUE(image->readable()) << image->uri << ": " << image->error;
    EXPECT_EQ(image->mime_type, "image/jpeg");
    EXPECT_EQ(image->rgba8.size(), std::size_t(image->width) * image->height * 4);
    decoded.insert(image->uri);
  }
  EXPECT_EQ(decoded, (std::set<std::string>{"artezin_bottle.jpg", "Wood_Cherry_Original_.jpg",
                                            "_2004_old_vine_zinfandel_btl_xlg.jpg"}));
  std::size_t textured = 0;
  for (const Material& mat : m.materials->materials) textured += mat.base_color_texture.present();
  EXPECT_EQ(textured, 3u);
  for (MaterialSlot s : m.mesh.face_material) ASSERT_LT(s, m.materials->materials.size());
  ASSERT_GE(m.parts.size(), 2u);
  std::set<std::string> names;  // the rack's Collada names repeat per instance: made unique as Blender does
  for (const MeshPart& p : m.parts) names.insert(p.name);
  EXPECT_EQ(names.size(), m.parts.size());
  EXPECT_TRUE(names.count("bottle.001") || std::any_of(names.begin(), names.end(), [](const std::string& n) {
                return n.size() > 4 && n.compare(n.size() - 4, 4, ".001") == 0;
              }));
  std::uint32_t triangles = 0;
  for (const MeshPart& p : m.parts) {
    EXPECT_EQ(p.first_triangle, triangles);
    triangles += p.triangle_count;
  }
  EXPECT_EQ(triangles, m.mesh.triangle_count());
  EXPECT_EQ(m.parts.back().first_vertex + m.parts.back().vertex_count, m.mesh.vertex_count());
}

// Collada from Blender: a cube, a torus and Suzanne, two untextured materials.
TEST(Qt3dAssets, TestSceneColladaHasThreePartsAndTwoMaterials) {
  const LoadedModel m = load_model(qt3d("test_scene.dae"));
  EXPECT_EQ(m.mesh.triangle_count(), 2132u);
  ASSERT_EQ(m.parts.size(), 3u);
  ASSERT_TRUE(m.materials);
  EXPECT_EQ(m.materials->materials.size(), 2u);
  EXPECT_TRUE(m.materials->images.empty());
  EXPECT_FALSE(m.materials->has_textures());
}

// OBJ from Blender without a material library: no MaterialSet, the object keeps its colour.
TEST(Qt3dAssets, ToyPlaneObjHasNoMaterials) {
  MeshLoadOptions ignore;
  ignore.ignore_loose = true;
  const LoadedModel m = load_model(qt3d("obj/toyplane.obj"), ignore);
  EXPECT_GT(m.mesh.triangle_count(), 7000u);
  EXPECT_FALSE(m.materials);
  EXPECT_TRUE(m.parts.empty());
}

}  // namespace
}  // namespace trispline::core
