// glTF materials and textures through load and export (core/mesh/gltf_io.h read_gltf_model / write_glb,
// material_image.h): small textured files written here, PNGs made with OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/mesh/gltf_io.h"
#include "core/mesh/material_image.h"
#include "core/mesh/mesh_io.h"

namespace fs = std::filesystem;
using namespace trispline::core;
using nlohmann::json;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("trispline_gltf_materials_" + name);
  fs::remove_all(d);
  fs::create_directories(d / "model");
  return d;
}

void write_bytes(const fs::path& p, const std::vector<std::uint8_t>& b) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// A w × h RGBA picture: pixel (x, y) = (x·40, y·40, 200, 255 − x), distinct per pixel.
std::vector<std::uint8_t> pattern(int w, int h) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &px[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = static_cast<std::uint8_t>(x * 40), p[1] = static_cast<std::uint8_t>(y * 40), p[2] = 200;
      p[3] = static_cast<std::uint8_t>(255 - x);
    }
  return px;
}

// PNG bytes written by OpenImageIO (independently of encode_png_rgba8).
std::vector<std::uint8_t> oiio_png(int w, int h, const std::vector<std::uint8_t>& rgba) {
  namespace OIIO = OIIO_NAMESPACE;
  std::vector<std::uint8_t> out;
  OIIO::Filesystem::IOVecOutput proxy(out);
  auto png = OIIO::ImageOutput::create("x.png");
  EXPECT_TRUE(png);
  png->set_ioproxy(&proxy);
  OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  EXPECT_TRUE(png->open("x.png", spec));
  EXPECT_TRUE(png->write_image(OIIO::TypeDesc::UINT8, rgba.data()));
  png->close();
  return out;
}

// An uncompressed 32-bit TGA (top-left origin), written byte by byte.
std::vector<std::uint8_t> tga(int w, int h, const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint8_t> b(18, 0);
  b[2] = 2;  // uncompressed true colour
  b[12] = static_cast<std::uint8_t>(w), b[13] = static_cast<std::uint8_t>(w >> 8);
  b[14] = static_cast<std::uint8_t>(h), b[15] = static_cast<std::uint8_t>(h >> 8);
  b[16] = 32;
  b[17] = 0x28;  // 8 alpha bits, top-left origin
  for (std::size_t i = 0; i < rgba.size(); i += 4)
    b.insert(b.end(), {rgba[i + 2], rgba[i + 1], rgba[i], rgba[i + 3]});  // BGRA
  return b;
}

std::string base64(const std::vector<std::uint8_t>& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = in[i] << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (in[i] << 16) | (in[i + 1] << 8);
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

template <class T>
void append(std::vector<std::uint8_t>& buf, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
  buf.insert(buf.end(), p, p + v.size() * sizeof(T));
}

// A .gltf of one mesh (a unit quad, two triangles, UVs) whose two primitives each draw one triangle: primitive 0
// with material 0, primitive 1 with `second_material` (-1: none). Images as given in `images` (JSON array).
json quad_gltf(const json& materials, const json& textures, const json& images, const json& samplers,
               int second_material) {
  const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<std::uint16_t> idx = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> buf;
  append(buf, pos);
  append(buf, uv);
  append(buf, idx);
  json prim1 = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 3}};
  if (second_material >= 0) prim1["material"] = second_material;
  json j = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"name", "quad"}, {"mesh", 0}}}},
            {"meshes",
             {{{"primitives",
                {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}, prim1}}}}},
            {"buffers", {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}}},
            {"bufferViews",
             {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
              {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
              {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
            {"accessors",
             {{{"bufferView", 0},
               {"componentType", 5126},
               {"count", 4},
               {"type", "VEC3"},
               {"min", {0, 0, 0}},
               {"max", {1, 1, 0}}},
              {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
              {{"bufferView", 2}, {"byteOffset", 0}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}},
              {{"bufferView", 2}, {"byteOffset", 6}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
            {"materials", materials}};
  if (!textures.empty()) j["textures"] = textures;
  if (!images.empty()) j["images"] = images;
  if (!samplers.empty()) j["samplers"] = samplers;
  return j;
}

json one(const json& element) {
  json a = json::array();
  a.push_back(element);
  return a;
}

fs::path save_json(const fs::path& p, const json& j) {
  std::ofstream(p) << j.dump(1);
  return p;
}

json textured_material() {
  return {{"name", "painted"},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {1.0, 0.5, 0.25, 1.0}},
            {"baseColorTexture", {{"index", 0}}},
            {"metallicFactor", 0.0},
            {"roughnessFactor", 0.4}}},
          {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
          {"occlusionTexture", {{"index", 0}, {"strength", 0.7}}},
          {"emissiveFactor", {0.1, 0.2, 0.3}},
          {"alphaMode", "MASK"},
          {"alphaCutoff", 0.3},
          {"doubleSided", true}};
}

const json kPlain = {{"name", "plain"},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {0.2, 0.4, 0.6, 0.5}}, {"metallicFactor", 0.8}, {"roughnessFactor", 0.1}}},
                     {"alphaMode", "BLEND"}};
const json kSampler = {{"magFilter", 9728}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33648}};

void expect_same_material(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.base_color[c], b.base_color[c], 1e-6);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.emissive[c], b.emissive[c], 1e-6);
  EXPECT_EQ(a.base_color_texture.present(), b.base_color_texture.present());
  EXPECT_EQ(a.base_color_texture.sampler, b.base_color_texture.sampler);
  EXPECT_EQ(a.normal_texture.present(), b.normal_texture.present());
  EXPECT_NEAR(a.normal_texture.scale, b.normal_texture.scale, 1e-9);
  EXPECT_NEAR(a.occlusion_texture.scale, b.occlusion_texture.scale, 1e-9);
  EXPECT_NEAR(a.metallic, b.metallic, 1e-9);
  EXPECT_NEAR(a.roughness, b.roughness, 1e-9);
  EXPECT_EQ(a.alpha_mode, b.alpha_mode);
  EXPECT_NEAR(a.alpha_cutoff, b.alpha_cutoff, 1e-9);
  EXPECT_EQ(a.double_sided, b.double_sided);
}

}  // namespace

TEST(GltfMaterials, ExternalTextureLoadsWithMaterialsUvsAndPixels) {
  const fs::path dir = fresh_dir("external");
  const auto px = pattern(3, 2);
  const auto png = oiio_png(3, 2, px);
  fs::create_directories(dir / "model" / "tex");
  write_bytes(dir / "model" / "tex" / "paint.png", png);
  const fs::path file =
      save_json(dir / "model" / "q.gltf",
                quad_gltf(json::array({textured_material(), kPlain}), one({{"source", 0}, {"sampler", 0}}),
                          one({{"uri", "tex/paint.png"}}), one(kSampler), 1));
  const GltfModel m = read_gltf_model(file);
  ASSERT_TRUE(m.materials);
  ASSERT_EQ(m.materials->materials.size(), 2u);
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_TRUE(m.parts.empty());  // one mesh node
  const Material& a = m.materials->materials[0];
  EXPECT_EQ(a.name, "painted");
  EXPECT_NEAR(a.base_color[1], 0.5, 1e-12);
  EXPECT_EQ(a.base_color_texture.image, 0);
  EXPECT_EQ(a.base_color_texture.sampler.wrap_s, TextureWrap::ClampToEdge);
  EXPECT_EQ(a.base_color_texture.sampler.wrap_t, TextureWrap::MirroredRepeat);
  EXPECT_EQ(a.base_color_texture.sampler.mag_filter, TextureFilter::Nearest);
  EXPECT_EQ(a.base_color_texture.sampler.min_filter, TextureFilter::LinearMipmapLinear);
  EXPECT_NEAR(a.normal_texture.scale, 0.5, 1e-12);
  EXPECT_NEAR(a.occlusion_texture.scale, 0.7, 1e-12);
  EXPECT_NEAR(a.emissive[2], 0.3, 1e-12);
  EXPECT_EQ(a.alpha_mode, AlphaMode::Mask);
  EXPECT_NEAR(a.alpha_cutoff, 0.3, 1e-12);
  EXPECT_TRUE(a.double_sided);
  EXPECT_EQ(m.materials->materials[1].alpha_mode, AlphaMode::Blend);
  EXPECT_FALSE(m.materials->materials[1].base_color_texture.present());
  ASSERT_EQ(m.materials->images.size(), 1u);  // three textures of material 0 share one image
  const MaterialImage& img = *m.materials->images[0];
  EXPECT_TRUE(img.readable()) << img.error;
  EXPECT_EQ(img.uri, "tex/paint.png");
  EXPECT_EQ(img.mime_type, "image/png");
  EXPECT_EQ(img.encoded, png);
  EXPECT_EQ(img.width, 3);
  EXPECT_EQ(img.height, 2);
  EXPECT_EQ(img.rgba8, px);
  ASSERT_EQ(m.mesh.face_material.size(), 2u);
  EXPECT_EQ(m.mesh.face_material[0], 0);
  EXPECT_EQ(m.mesh.face_material[1], 1);
  ASSERT_EQ(m.mesh.uvs.size(), 8u);            // each primitive its own four vertices
  EXPECT_EQ(m.mesh.uvs[0], glm::dvec2(0, 1));  // TEXCOORD_0 as written (top-left origin)
  EXPECT_EQ(m.mesh.uvs[2], glm::dvec2(1, 0));
  // The geometry-only reader opens no image and keeps the legacy slots.
  EXPECT_TRUE(read_gltf_objects(file)[0].mesh.face_material.empty());
}

TEST(GltfMaterials, ExportKeepsMaterialsAndTheImageBytes) {
  const fs::path dir = fresh_dir("export");
  const auto png = oiio_png(3, 2, pattern(3, 2));
  write_bytes(dir / "model" / "paint.png", png);
  const fs::path file = save_json(dir / "model" / "q.gltf", quad_gltf(json::array({textured_material(), kPlain}),
                                                                      one({{"source", 0}, {"sampler", 0}}),
                                                                      one({{"uri", "paint.png"}}), one(kSampler), 1));
  const GltfModel m = read_gltf_model(file);
  GltfNode node;
  node.name = "quad";
  node.mesh = &m.mesh;
  node.materials = m.materials;
  GltfNode second = node;  // the same set on a second node is written once
  second.name = "quad2";
  write_glb(dir / "out.glb", {node, second});

  const GltfModel back = read_gltf_model(dir / "out.glb");
  ASSERT_TRUE(back.materials);
  ASSERT_EQ(back.materials->materials.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) expect_same_material(m.materials->materials[i], back.materials->materials[i]);
  ASSERT_EQ(back.materials->images.size(), 1u);
  EXPECT_EQ(back.materials->images[0]->encoded, png);  // the source bytes, not re-encoded
  EXPECT_EQ(back.materials->images[0]->mime_type, "image/png");
  // Each node: one primitive per slot, so every face keeps its slot.
  ASSERT_EQ(back.mesh.face_material.size(), 4u);
  EXPECT_EQ(back.mesh.face_material[0], 0);
  EXPECT_EQ(back.mesh.face_material[1], 1);
  EXPECT_EQ(back.mesh.face_material[3], 1);
  // Each slot's primitive holds the vertices its faces use: every corner keeps its position and UV.
  for (std::size_t f = 0; f < m.mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(back.mesh.uvs[back.mesh.triangles[f][c]], m.mesh.uvs[m.mesh.triangles[f][c]]);
      EXPECT_EQ(back.mesh.positions[back.mesh.triangles[f][c]], m.mesh.positions[m.mesh.triangles[f][c]]);
    }
  EXPECT_EQ(back.mesh.positions.size(), 12u);  // 3 + 3 per node: the vertices no face uses are left out
  // One material and one image per set in the file (tinygltf's view).
  tinygltf::Model raw;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&raw, &err, &warn, (dir / "out.glb").string())) << err;
  EXPECT_EQ(raw.materials.size(), 2u);
  EXPECT_EQ(raw.images.size(), 1u);
  EXPECT_EQ(raw.samplers.size(), 1u);
  EXPECT_EQ(raw.meshes[0].primitives.size(), 2u);
}

TEST(GltfMaterials, OtherFormatsAreEmbeddedAsPng) {
  const auto px = pattern(4, 3);
  const MaterialImage img = decode_material_image(tga(4, 3, px), "", "t", "t.tga");
  ASSERT_TRUE(img.readable()) << img.error;
  EXPECT_EQ(img.rgba8, px);
  const auto [bytes, mime] = gltf_image_bytes(img);
  EXPECT_EQ(mime, "image/png");
  const MaterialImage again = decode_material_image(bytes, mime, "", "");
  ASSERT_TRUE(again.readable()) << again.error;
  EXPECT_EQ(again.rgba8, px);
  // A PNG is embedded as it is.
  const auto png = oiio_png(4, 3, px);
  EXPECT_EQ(gltf_image_bytes(decode_material_image(png, "", "", "")).first, png);
  // An unreadable image embeds nothing.
  EXPECT_TRUE(gltf_image_bytes(decode_material_image({1, 2, 3}, "image/png", "", "")).first.empty());
}

TEST(GltfMaterials, GreyImageBecomesRgbWithOpaqueAlpha) {
  namespace OIIO = OIIO_NAMESPACE;
  std::vector<std::uint8_t> out;
  OIIO::Filesystem::IOVecOutput proxy(out);
  auto png = OIIO::ImageOutput::create("g.png");
  png->set_ioproxy(&proxy);
  const std::uint8_t grey[2] = {10, 250};
  ASSERT_TRUE(png->open("g.png", OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(png->write_image(OIIO::TypeDesc::UINT8, grey));
  png->close();
  const MaterialImage img = decode_material_image(out, "", "", "");
  ASSERT_TRUE(img.readable()) << img.error;
  EXPECT_EQ(img.rgba8, (std::vector<std::uint8_t>{10, 10, 10, 255, 250, 250, 250, 255}));
}

TEST(GltfMaterials, ImageUriOutsideTheFolderIsRefusedButTheObjectLoads) {
  const fs::path dir = fresh_dir("escape");
  write_bytes(dir / "secret.png", oiio_png(2, 2, pattern(2, 2)));
  const fs::path file =
      save_json(dir / "model" / "q.gltf", quad_gltf(json::array({textured_material()}), one({{"source", 0}}),
                                                    one({{"uri", "../secret.png"}}), json::array(), 0));
  const GltfModel m = read_gltf_model(file);
  ASSERT_TRUE(m.materials);
  ASSERT_EQ(m.materials->images.size(), 1u);
  const MaterialImage& img = *m.materials->images[0];
  EXPECT_FALSE(img.readable());
  EXPECT_TRUE(img.encoded.empty());
  EXPECT_NE(img.error.find("outside the folder"), std::string::npos) << img.error;
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("../secret.png"), std::string::npos) << m.warnings[0];
  EXPECT_EQ(m.mesh.triangles.size(), 2u);
  // Absolute paths and schemes too.
  for (const char* uri : {"/etc/passwd", "file:///etc/passwd"}) {
    save_json(file, quad_gltf(json::array({textured_material()}), one({{"source", 0}}), one({{"uri", uri}}),
                              json::array(), 0));
    const GltfModel r = read_gltf_model(file);
    EXPECT_FALSE(r.materials->images[0]->readable()) << uri;
    EXPECT_TRUE(r.materials->images[0]->encoded.empty()) << uri;
  }
}

TEST(GltfMaterials, MissingTextureLoadsWithAnErrorAndExportsWithoutIt) {
  const fs::path dir = fresh_dir("missing");
  const fs::path file =
      save_json(dir / "model" / "q.gltf", quad_gltf(json::array({textured_material()}), one({{"source", 0}}),
                                                    one({{"uri", "gone.png"}}), json::array(), 0));
  const GltfModel m = read_gltf_model(file);
  ASSERT_TRUE(m.materials);
  const MaterialImage& img = *m.materials->images[0];
  EXPECT_FALSE(img.readable());
  EXPECT_EQ(img.uri, "gone.png");
  EXPECT_NE(img.error.find("file not found"), std::string::npos) << img.error;
  EXPECT_TRUE(m.materials->materials[0].base_color_texture.present());  // the viewport shows a placeholder
  GltfNode node;
  node.name = "q";
  node.mesh = &m.mesh;
  node.materials = m.materials;
  write_glb(dir / "out.glb", {node});
  const GltfModel back = read_gltf_model(dir / "out.glb");
  ASSERT_TRUE(back.materials);
  EXPECT_TRUE(back.materials->images.empty());
  EXPECT_FALSE(back.materials->materials[0].base_color_texture.present());
  EXPECT_EQ(back.materials->materials[0].name, "painted");
}

TEST(GltfMaterials, DataUriImageAndThePrimitiveWithoutMaterial) {
  const fs::path dir = fresh_dir("datauri");
  const auto px = pattern(2, 2);
  const auto png = oiio_png(2, 2, px);
  const fs::path file = save_json(dir / "model" / "q.gltf",
                                  quad_gltf(json::array({textured_material()}), one({{"source", 0}}),
                                            one({{"uri", "data:image/png;base64," + base64(png)}}), json::array(), -1));
  const GltfModel m = read_gltf_model(file);
  ASSERT_TRUE(m.materials);
  const MaterialImage& img = *m.materials->images[0];
  ASSERT_TRUE(img.readable()) << img.error;
  EXPECT_EQ(img.encoded, png);
  EXPECT_EQ(img.rgba8, px);
  EXPECT_TRUE(img.uri.empty());
  // Second primitive without a material: the glTF default material appended.
  ASSERT_EQ(m.materials->materials.size(), 2u);
  EXPECT_EQ(m.materials->materials[1].base_color, glm::dvec4(1.0));
  EXPECT_EQ(m.mesh.face_material[1], 1);
}

TEST(GltfMaterials, HugeDeclaredImageIsRefusedBeforeDecoding) {
  auto png = oiio_png(2, 2, pattern(2, 2));
  // IHDR: width and height at bytes 16..23, its CRC at 29..32 (over type + data, bytes 12..28).
  auto be32 = [&](std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) png[at + i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
  };
  be32(16, 60000);
  be32(20, 60000);
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 12; i < 29; ++i) {
    crc ^= png[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  be32(29, crc ^ 0xFFFFFFFFu);
  const MaterialImage img = decode_material_image(png, "image/png", "huge", "");
  EXPECT_FALSE(img.readable());
  EXPECT_TRUE(img.rgba8.empty());
  EXPECT_NE(img.error.find("60000 × 60000"), std::string::npos) << img.error;
  EXPECT_NE(img.error.find("limit"), std::string::npos) << img.error;
  // Within the side limit but over a small byte budget: refused by the budget.
  const MaterialImage small = decode_material_image(oiio_png(64, 64, pattern(64, 64)), "", "", "", 1000);
  EXPECT_FALSE(small.readable());
  EXPECT_NE(small.error.find("limit"), std::string::npos) << small.error;
}

TEST(GltfMaterials, SeveralNodesBecomePartsAndExportAsANodeTree) {
  const fs::path dir = fresh_dir("parts");
  json j = quad_gltf(json::array({kPlain}), json::array(), json::array(), json::array(), 0);
  j["meshes"].push_back(j["meshes"][0]);  // mesh 1: the same quad again
  j["nodes"] = {{{"name", "root"}, {"children", {1, 2, 3}}, {"translation", {0, 0, 5}}},
                {{"name", "a"}, {"mesh", 0}, {"translation", {1, 0, 0}}},
                {{"name", "b"}, {"mesh", 0}, {"translation", {3, 0, 0}}},
                {{"name", "c"}, {"mesh", 1}, {"scale", {2, 2, 2}}}};
  const GltfModel m = read_gltf_model(save_json(dir / "model" / "n.gltf", j));
  ASSERT_EQ(m.parts.size(), 3u);
  EXPECT_EQ(m.parts[0].name, "a");
  EXPECT_EQ(m.parts[1].mesh_index, 0);
  EXPECT_EQ(m.parts[2].mesh_index, 1);
  EXPECT_EQ(m.parts[1].first_vertex, 8u);
  EXPECT_EQ(m.parts[2].first_triangle, 4u);
  EXPECT_EQ(m.parts[2].triangle_count, 2u);
  EXPECT_EQ(m.parts[1].world[3], glm::dvec4(3, 0, 5, 1));
  EXPECT_EQ(m.mesh.positions[8], glm::dvec3(3, 0, 5));  // rest mesh: node transforms applied

  GltfNode node;
  node.name = "tree";
  node.mesh = &m.mesh;
  node.materials = m.materials;
  node.parts = &m.parts;
  node.rest_mesh = &m.mesh;
  node.object_to_world = glm::dmat4(1.0);
  node.object_to_world[3] = glm::dvec4(0, 10, 0, 1);
  write_glb(dir / "tree.glb", {node});
  tinygltf::Model raw;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&raw, &err, &warn, (dir / "tree.glb").string())) << err;
  ASSERT_EQ(raw.nodes.size(), 4u);
  EXPECT_EQ(raw.nodes[0].name, "tree");
  EXPECT_EQ(raw.nodes[1].name, "tree/a");
  EXPECT_EQ(raw.nodes[3].name, "tree/c");
  EXPECT_EQ(raw.meshes.size(), 2u);  // a and b are instances of one mesh
  EXPECT_EQ(raw.nodes[1].mesh, raw.nodes[2].mesh);
  const GltfModel back = read_gltf_model(dir / "tree.glb");
  ASSERT_EQ(back.mesh.positions.size(), m.mesh.positions.size());
  for (std::size_t i = 0; i < m.mesh.positions.size(); ++i)
    EXPECT_NEAR(glm::length(back.mesh.positions[i] - (m.mesh.positions[i] + glm::dvec3(0, 10, 0))), 0.0, 1e-5);
  ASSERT_EQ(back.parts.size(), 3u);
  EXPECT_EQ(back.parts[2].name, "tree/c");
}

TEST(GltfMaterials, InsideFacesKeepTheirSlotBesideMaterials) {
  const fs::path dir = fresh_dir("inside");
  const fs::path file = save_json(dir / "model" / "q.gltf",
                                  quad_gltf(json::array({kPlain}), json::array(), json::array(), json::array(), 0));
  GltfModel m = read_gltf_model(file);
  m.mesh.face_material = {0, kMaterialInside};
  GltfNode node;
  node.name = "cut";
  node.mesh = &m.mesh;
  node.materials = m.materials;
  write_glb(dir / "cut.glb", {node});
  const GltfModel back = read_gltf_model(dir / "cut.glb");
  ASSERT_TRUE(back.materials);
  EXPECT_EQ(back.materials->materials.size(), 1u);  // "cut.inside" is no material of the set
  EXPECT_EQ(back.mesh.face_material, (std::vector<MaterialSlot>{0, kMaterialInside}));
  EXPECT_EQ(back.mesh.positions.size(), 8u);  // the inside primitive shares the vertices
}
