// load_model on assimp formats (core/mesh/model_load.h): OBJ + MTL materials, textures read from the model's folder
// only, the MTL checks, Collada parts, uvs in glTF's convention.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/mesh/material_image.h"
#include "core/mesh/model_load.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;
using test::write_text;
using ::testing::HasSubstr;

void write_bytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A w × h PNG whose pixel (x, y) is (x·40, y·40, 200, alpha).
std::vector<std::uint8_t> png(int w, int h, std::uint8_t alpha = 255) {
  std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &rgba[(std::size_t(y) * w + x) * 4];
      p[0] = std::uint8_t(x * 40), p[1] = std::uint8_t(y * 40), p[2] = 200, p[3] = alpha;
    }
  return encode_png_rgba8(w, h, rgba);
}

// Two quads (4 triangles), the first with material "skin", the second with "leaf".
const std::string kTwoQuads =
    "mtllib two.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl skin\nf 1/1 2/2 3/3 4/4\n"
    "usemtl leaf\nf 2/1 5/2 6/3 3/4\n";

TEST(ModelLoad, ObjMtlMaterialsTexturesAndAlpha) {
  TempDir dir;
  write_text(dir / "two.obj", kTwoQuads);
  write_text(dir / "two.mtl",
             "# made by hand\nnewmtl skin\nKd 0.8 0.2 0.1\nKs 0.5 0.5 0.5\nNs 250\nmap_Kd tex/skin.png\n"
             "bump -bm 0.5 tex/normal.png\nKe 0.1 0 0\n\nnewmtl leaf\nKd 1 1 1\nd 0.5\nmap_Kd tex/leaf.png\n"
             "map_d tex/mask.png\n");
  std::filesystem::create_directories(dir / "tex");
  write_bytes(dir / "tex/skin.png", png(4, 2));
  write_bytes(dir / "tex/normal.png", png(2, 2));
  write_bytes(dir / "tex/leaf.png", png(2, 2));
  write_bytes(dir / "tex/mask.png", png(4, 4, 0));

  MeshLoadReport report;
  const LoadedModel m = load_model(dir / "two.obj", {}, &report);
  EXPECT_EQ(report.loader, "assimp");
  ASSERT_EQ(m.mesh.triangle_count(), 4u);
  ASSERT_EQ(m.mesh.face_material.size(), 4u);
  EXPECT_EQ(m.mesh.face_material, (std::vector<MaterialSlot>{0, 0, 1, 1}));
  ASSERT_TRUE(m.materials);
  ASSERT_EQ(m.materials->materials.size(), 2u);
  const Material& skin = m.materials->materials[0];
  EXPECT_EQ(skin.name, "skin");
  EXPECT_NEAR(skin.base_color.x, 0.8, 1e-6);
  EXPECT_NEAR(skin.base_color.y, 0.2, 1e-6);
  EXPECT_EQ(skin.base_color.w, 1.0);
  EXPECT_EQ(skin.alpha_mode, AlphaMode::Opaque);
  EXPECT_NEAR(skin.roughness, 1.0 - std::sqrt(0.25), 1e-6);  // Blender's estimate from Ns 250
  EXPECT_EQ(skin.metallic, 0.0);
  EXPECT_NEAR(skin.emissive.x, 0.1, 1e-6);
  ASSERT_TRUE(skin.base_color_texture.present());
  const MaterialImage& skin_image = *m.materials->images[std::size_t(skin.base_color_texture.image)];
  EXPECT_TRUE(skin_image.readable()) << skin_image.error;
  EXPECT_EQ(skin_image.width, 4);
  EXPECT_EQ(skin_image.height, 2);
  EXPECT_EQ(skin_image.mime_type, "image/png");
  EXPECT_EQ(skin_image.uri, "tex/skin.png");
  ASSERT_TRUE(skin.normal_texture.present());
  EXPECT_NEAR(skin.normal_texture.scale, 0.5, 1e-6);

  const Material& leaf = m.materials->materials[1];
  EXPECT_EQ(leaf.alpha_mode, AlphaMode::Mask);  // map_d: a cut-out
  EXPECT_EQ(leaf.alpha_cutoff, 0.5);
  EXPECT_NEAR(leaf.base_color.w, 0.5, 1e-6);
  ASSERT_TRUE(leaf.base_color_texture.present());
  const MaterialImage& combined = *m.materials->images[std::size_t(leaf.base_color_texture.image)];
  ASSERT_TRUE(combined.readable());
  EXPECT_EQ(combined.width, 2);
  EXPECT_EQ(combined.rgba8[3], 0);   // alpha from the mask (all 0)
  EXPECT_EQ(combined.rgba8[4], 40);  // red of leaf.png's pixel (1, 0)
  EXPECT_FALSE(combined.encoded.empty());
  EXPECT_TRUE(m.texture_errors().empty());
  EXPECT_TRUE(m.warnings.empty());

  // uvs in glTF's convention: the OBJ's vt 0 0 (bottom left) is v = 1.
  ASSERT_EQ(m.mesh.uvs.size(), m.mesh.vertex_count());
  EXPECT_EQ(m.mesh.uvs[0], glm::dvec2(0, 1));
  // load_mesh reads the same mesh, without materials.
  const TriMesh plain = load_mesh(dir / "two.obj");
  EXPECT_EQ(plain.positions, m.mesh.positions);
  EXPECT_EQ(plain.uvs, m.mesh.uvs);
  EXPECT_TRUE(plain.face_material.empty());
}

TEST(ModelLoad, TexturesOutsideTheFolderMissingOrBrokenLoadTheObjectWithAnError) {
  TempDir dir;
  std::filesystem::create_directories(dir / "model");
  write_bytes(dir / "secret.png", png(2, 2));
  write_text(dir / "model/a.obj", kTwoQuads);
  write_text(dir / "model/two.mtl",
             "newmtl skin\nmap_Kd ../secret.png\nnewmtl leaf\nmap_Kd gone.png\nnorm /etc/passwd\nmap_Ke broken.png\n");
  write_text(dir / "model/broken.png", "not an image");
  const LoadedModel m = load_model(dir / "model/a.obj");
  EXPECT_EQ(m.mesh.triangle_count(), 4u);
  ASSERT_TRUE(m.materials);
  const std::vector<std::string> errors = m.texture_errors();
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_THAT(errors[0], HasSubstr("outside the folder"));
  EXPECT_THAT(errors[1], HasSubstr("gone.png': file not found"));
  EXPECT_THAT(errors[2], HasSubstr("is an absolute path"));
  EXPECT_THAT(errors[3], HasSubstr("cannot decode PNG"));
  for (const auto& image : m.materials->images) EXPECT_TRUE(image->rgba8.empty());
}

TEST(ModelLoad, MaterialLibrariesComeFromTheModelsFolderOnly) {
  TempDir dir;
  std::filesystem::create_directories(dir / "model");
  write_text(dir / "outside.mtl", "newmtl skin\nKd 1 0 0\n");
  write_text(dir / "model/a.obj", "mtllib ../outside.mtl\n" + kTwoQuads.substr(kTwoQuads.find('\n') + 1));
  const LoadedModel m = load_model(dir / "model/a.obj");
  EXPECT_EQ(m.mesh.triangle_count(), 4u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_THAT(m.warnings[0], HasSubstr("outside the folder"));
  ASSERT_TRUE(m.materials);  // usemtl names stay, with default values
  EXPECT_EQ(m.materials->materials[0].name, "skin");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.materials->materials[0].base_color[c], 0.6, 1e-6);  // assimp's default Kd
  EXPECT_EQ(m.materials->materials[0].base_color.w, 1.0);
  // An OBJ naming itself, or the name assimp is served it under, as its library: the text served as MTL is the
  // file's MTL statements only (none here), never the model's bytes (assimp's MTL reader wrote through a null
  // material on them: a segfault).
  write_text(dir / "model/self.obj", "mtllib self.obj\nnormals, two groups\nmtllib mesh.obj\n" + kTwoQuads);
  const LoadedModel self = load_model(dir / "model/self.obj");
  EXPECT_EQ(self.mesh.triangle_count(), 4u);
  ASSERT_EQ(self.warnings.size(), 2u);  // mesh.obj and two.mtl are not there
  EXPECT_THAT(self.warnings[0], HasSubstr("/model/mesh.obj': file not found"));
  write_text(dir / "model/zero.obj", "mtllib /dev/zero\n" + kTwoQuads.substr(kTwoQuads.find('\n') + 1));
  const LoadedModel zero = load_model(dir / "model/zero.obj");
  ASSERT_EQ(zero.warnings.size(), 1u);
  EXPECT_THAT(zero.warnings[0], HasSubstr("absolute path"));
}

TEST(ModelLoad, MtlStatementsBeforeNewmtlAreRefused) {
  TempDir dir;  // assimp 5.2 writes them through a null material
  write_text(dir / "two.obj", kTwoQuads);
  write_text(dir / "two.mtl", "Kd 1 0 0\nnewmtl skin\n");
  try {
    load_model(dir / "two.obj");
    FAIL() << "expected a refusal";
  } catch (const MeshIoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("line 1: 'Kd' before any newmtl"));
  }
  write_text(dir / "two.mtl", "newmtl skin\nKd 1 0 0" + std::string(1, '\0') + "\n");
  EXPECT_THROW(load_model(dir / "two.obj"), MeshIoError);
}

TEST(ModelLoad, ObjWithoutMaterialsKeepsTheObjectColour) {
  TempDir dir;
  write_text(dir / "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const LoadedModel m = load_model(dir / "plain.obj");
  EXPECT_FALSE(m.materials);
  EXPECT_TRUE(m.mesh.face_material.empty());
  EXPECT_TRUE(m.parts.empty());
}

// Two nodes instancing one mesh, a third node with another mesh and material: three parts, two shapes.
const char* kColladaScene = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_images><image id="img"><init_from>wood.png</init_from></image></library_images>
  <library_effects>
    <effect id="red-fx"><profile_COMMON><technique sid="t"><lambert>
      <diffuse><color>1 0 0 1</color></diffuse></lambert></technique></profile_COMMON></effect>
    <effect id="wood-fx"><profile_COMMON>
      <newparam sid="s"><surface type="2D"><init_from>img</init_from></surface></newparam>
      <newparam sid="smp"><sampler2D><source>s</source></sampler2D></newparam>
      <technique sid="t"><phong><diffuse><texture texture="smp" texcoord="UV"/></diffuse>
      <shininess><float>50</float></shininess></phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="red" name="red"><instance_effect url="#red-fx"/></material>
    <material id="wood" name="wood"><instance_effect url="#wood-fx"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="tri"><mesh>
      <source id="tri-p"><float_array id="tri-pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pa" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <source id="tri-t"><float_array id="tri-ta" count="6">0 0 1 0 0 1</float_array>
        <technique_common><accessor source="#tri-ta" count="3" stride="2">
          <param name="S" type="float"/><param name="T" type="float"/></accessor></technique_common></source>
      <vertices id="tri-v"><input semantic="POSITION" source="#tri-p"/></vertices>
      <triangles material="m" count="1"><input semantic="VERTEX" source="#tri-v" offset="0"/>
        <input semantic="TEXCOORD" source="#tri-t" offset="0" set="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="scene">
    <node id="a" name="left"><translate>-2 0 0</translate>
      <instance_geometry url="#tri"><bind_material><technique_common>
        <instance_material symbol="m" target="#red"/></technique_common></bind_material></instance_geometry></node>
    <node id="b" name="right"><translate>2 0 0</translate>
      <instance_geometry url="#tri"><bind_material><technique_common>
        <instance_material symbol="m" target="#red"/></technique_common></bind_material></instance_geometry></node>
    <node id="c" name="top"><translate>0 3 0</translate>
      <instance_geometry url="#tri"><bind_material><technique_common>
        <instance_material symbol="m" target="#wood"><bind_vertex_input semantic="UV" input_semantic="TEXCOORD"
          input_set="0"/></instance_material></technique_common></bind_material></instance_geometry></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";

TEST(ModelLoad, ColladaNodesBecomePartsWithTheirMaterials) {
  TempDir dir;
  write_text(dir / "scene.dae", kColladaScene);
  write_bytes(dir / "wood.png", png(3, 3));
  const LoadedModel m = load_model(dir / "scene.dae");
  ASSERT_EQ(m.mesh.triangle_count(), 3u);
  ASSERT_EQ(m.parts.size(), 3u);
  EXPECT_EQ(m.parts[0].name, "left");
  EXPECT_EQ(m.parts[2].name, "top");
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(m.parts[i].first_triangle, i);
    EXPECT_EQ(m.parts[i].triangle_count, 1u);
    EXPECT_EQ(m.parts[i].first_vertex, 3 * i);  // welded within a part only
    EXPECT_EQ(m.parts[i].vertex_count, 3u);
  }
  EXPECT_EQ(m.parts[0].mesh_index, m.parts[1].mesh_index);  // instances of one mesh and material
  EXPECT_NE(m.parts[0].mesh_index, m.parts[2].mesh_index);
  EXPECT_NEAR(m.parts[1].world[3].x, 2.0, 1e-12);
  EXPECT_NEAR(m.mesh.positions[3].x, 2.0, 1e-12);  // node transforms applied
  ASSERT_TRUE(m.materials);
  ASSERT_EQ(m.materials->materials.size(), 2u);
  EXPECT_EQ(m.mesh.face_material, (std::vector<MaterialSlot>{0, 0, 1}));
  EXPECT_EQ(m.materials->materials[0].name, "red");
  EXPECT_EQ(m.materials->materials[0].base_color, glm::dvec4(1, 0, 0, 1));
  const Material& wood = m.materials->materials[1];
  ASSERT_TRUE(wood.base_color_texture.present());
  EXPECT_TRUE(m.materials->images[std::size_t(wood.base_color_texture.image)]->readable());
  EXPECT_NEAR(wood.roughness, 1.0 - std::sqrt(0.05), 1e-6);
  // load_mesh accepts Collada too, with the same triangles.
  EXPECT_EQ(load_mesh(dir / "scene.dae").positions, m.mesh.positions);
}

TEST(ModelLoad, ColladaAndFbxAreCheckedBeforeParsing) {
  TempDir dir;
  write_text(dir / "x.dae", "COLLADA? no");
  EXPECT_THAT([&] { load_model(dir / "x.dae"); }, ::testing::ThrowsMessage<MeshIoError>(HasSubstr("not a Collada")));
  write_text(dir / "x.fbx", std::string("; FBX\0\0", 7));
  EXPECT_THAT([&] { load_model(dir / "x.fbx"); }, ::testing::ThrowsMessage<MeshIoError>(HasSubstr("NUL byte")));
  write_text(dir / "empty.fbx", "");
  EXPECT_THROW(load_mesh(dir / "empty.fbx"), MeshIoError);
}

}  // namespace
}  // namespace trispline::core
