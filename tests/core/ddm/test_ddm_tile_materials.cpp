// Texture-mapped tiles (seed Fig. 5.12): a tile's own uvs and materials ride on every copy (ddm_evaluate, the
// paint path's reuse), several tiles' materials join into one set (ddm_tile_materials), a layer export carries them.
#include <gtest/gtest.h>

#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/scene/primitives.h"

namespace trispline::core {
namespace {

// The hex tile with uvs from its (x, y) mirrored and two materials (alternate faces), one texture.
DdmTile textured_hex() {
  TriMesh mesh = make_ddm_tile("hex").mesh;
  for (glm::dvec3& p : mesh.positions) p *= glm::dvec3(2.0, 3.0, 0.5);  // any units: canonical_ddm_tile fits it
  mesh.uvs.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) mesh.uvs[v] = {1.0 - mesh.positions[v].x, mesh.positions[v].y};
  mesh.face_material.assign(mesh.triangle_count(), 0);
  for (std::size_t f = 1; f < mesh.triangle_count(); f += 2) mesh.face_material[f] = 1;
  auto set = std::make_shared<MaterialSet>();
  auto image = std::make_shared<MaterialImage>();
  image->name = "planks";
  image->width = image->height = 1;
  image->rgba8 = {200, 120, 40, 255};
  set->images.push_back(image);
  Material wood, leaf;
  wood.name = "wood";
  wood.base_color_texture.image = 0;
  leaf.name = "leaf";
  leaf.alpha_mode = AlphaMode::Mask;
  set->materials = {wood, leaf};
  return canonical_ddm_tile(mesh, "crate", set);
}

TEST(DdmTileMaterials, ATextureMappedTileKeepsItsUvsAndMaterials) {
  const DdmTile tile = textured_hex();
  ASSERT_TRUE(tile.materials);
  EXPECT_EQ(tile.mesh.uvs.size(), tile.mesh.vertex_count());
  EXPECT_EQ(tile.mesh.face_material.size(), tile.mesh.triangle_count());
  // Without materials the tile keeps neither, as before.
  TriMesh plain = tile.mesh;
  const DdmTile untextured = canonical_ddm_tile(plain, "plain");
  EXPECT_FALSE(untextured.materials);
  EXPECT_TRUE(untextured.mesh.uvs.empty());
  EXPECT_TRUE(untextured.mesh.face_material.empty());
  // Materials but no uvs: the tile's (x, y) from above.
  plain.uvs.clear();
  const DdmTile projected = canonical_ddm_tile(plain, "projected", tile.materials);
  ASSERT_EQ(projected.mesh.uvs.size(), projected.mesh.vertex_count());
  for (std::size_t v = 0; v < projected.mesh.vertex_count(); v += 5) {
    EXPECT_NEAR(projected.mesh.uvs[v].x, projected.mesh.positions[v].x, 1e-12);
    EXPECT_NEAR(projected.mesh.uvs[v].y, projected.mesh.positions[v].y, 1e-12);
  }
}

TEST(DdmTileMaterials, SetsJoinWithImagesReindexedAndPlainTilesGetTheLayersColour) {
  const DdmTile a = textured_hex(), b = textured_hex();
  const DdmTileMaterials one = ddm_tile_materials({a});
  EXPECT_EQ(one.set.get(), a.materials.get()) << "a single textured tile's set is used as it is";
  EXPECT_FALSE(ddm_tile_materials({make_ddm_tile("thorn")}).set);
  const DdmTileMaterials joined = ddm_tile_materials({a, make_ddm_tile("thorn"), b});
  ASSERT_TRUE(joined.set);
  EXPECT_EQ(joined.first_slot, (std::vector<MaterialSlot>{0, 2, 3}));
  ASSERT_EQ(joined.set->materials.size(), 5u);
  EXPECT_EQ(joined.set->materials[2].name, "thorn");
  EXPECT_EQ(joined.set->materials[2].base_color, glm::dvec4(1.0)) << "white unless a colour is given";
  EXPECT_EQ(joined.set->materials[2].metallic, 0.0) << "plain tiles are not metal";
  const glm::dvec3 brick(0.7, 0.3, 0.22);
  const DdmTileMaterials coloured = ddm_tile_materials({a, make_ddm_tile("thorn"), b}, brick);
  EXPECT_EQ(coloured.set->materials[2].base_color, glm::dvec4(brick, 1.0)) << "a plain tile shows the layer's colour";
  EXPECT_EQ(coloured.set->materials[0].base_color, joined.set->materials[0].base_color) << "textured ones keep theirs";
  EXPECT_EQ(joined.set->images.size(), 2u);
  EXPECT_EQ(joined.set->materials[0].base_color_texture.image, 0);
  EXPECT_EQ(joined.set->materials[3].base_color_texture.image, 1);
  EXPECT_EQ(joined.set->materials[4].alpha_mode, AlphaMode::Mask);
}

DdmLayer sphere_layer(const std::vector<DdmInstance>& instances) {
  DdmLayer layer;
  layer.name = "crates";
  layer.tiles = {textured_hex(), make_ddm_tile("thorn")};
  layer.tile_sources = {"crate.obj", "thorn"};
  layer.surface = std::make_shared<DdmSubdivBase>(make_sphere(8, 4));
  layer.instances = instances;
  layer.height = 0.1;
  ddm_layer_finish(layer, {9, 9});
  return layer;
}

TEST(DdmTileMaterials, EveryCopyCarriesItsTilesUvsAndSlotsAndPaintingReusesThemExactly) {
  const DdmLayer layer = sphere_layer({{0, {0, 0}, {1, 1}, 0}, {3, {0, 0}, {1, 1}, 1}, {5, {0, 0}, {1, 1}, 0}});
  const TriMesh& m = *layer.mesh;
  const DdmTile& hex = layer.tiles[0];
  const std::size_t nv = hex.mesh.vertex_count(), nf = hex.mesh.triangle_count();
  const std::size_t thorn_v = layer.tiles[1].mesh.vertex_count(), thorn_f = layer.tiles[1].mesh.triangle_count();
  ASSERT_EQ(m.uvs.size(), m.vertex_count());
  ASSERT_EQ(m.face_material.size(), m.triangle_count());
  for (std::size_t v = 0; v < nv; ++v) {
    ASSERT_EQ(m.uvs[v], hex.mesh.uvs[v]);                 // first copy
    ASSERT_EQ(m.uvs[nv + thorn_v + v], hex.mesh.uvs[v]);  // third copy
  }
  for (std::size_t f = 0; f < nf; ++f) ASSERT_EQ(m.face_material[f], hex.mesh.face_material[f]);
  for (std::size_t f = 0; f < thorn_f; ++f) ASSERT_EQ(m.face_material[nf + f], 2) << "the thorn's default material";
  // Painting one more instance reuses the copies and evaluates the new one: bit for bit a full evaluation.
  const auto grown = ddm_layer_with_instances(
      layer, {{0, {0, 0}, {1, 1}, 0}, {3, {0, 0}, {1, 1}, 1}, {5, {0, 0}, {1, 1}, 0}, {7, {0, 0}, {1, 1}, 0}});
  const TriMesh full = ddm_layer_mesh(*grown, 0.0);
  EXPECT_EQ(grown->mesh->uvs, full.uvs);
  EXPECT_EQ(grown->mesh->face_material, full.face_material);
  EXPECT_EQ(grown->mesh->positions, full.positions);
}

TEST(DdmTileMaterials, AMorphedTileKeepsItsMaterials) {
  const DdmTile a = textured_hex();
  const DdmTile half = ddm_morph(a, a, 0.5);
  EXPECT_EQ(half.materials.get(), a.materials.get());
  EXPECT_EQ(half.mesh.uvs, a.mesh.uvs);
}

}  // namespace
}  // namespace trispline::core
