// assimp materials → MaterialSet. See assimp_material.h for the mapping.
#include "core/mesh/assimp_material.h"

#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/texture.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "core/mesh/material_image.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/model_load.h"

namespace trispline::core {
namespace {

struct ImageTable {
  const aiScene& scene;
  const std::filesystem::path& model;
  MaterialSet& set;
  std::map<std::string, int> by_path;  // texture path as written → index into set.images

  // The image a material texture path names (decoded once per path).
  int image(const std::string& written) {
    if (const auto it = by_path.find(written); it != by_path.end()) return it->second;
    const int index = static_cast<int>(set.images.size());
    by_path.emplace(written, index);
    std::string uri = written;
    std::replace(uri.begin(), uri.end(), '\\', '/');
    const std::string name = std::filesystem::path(uri).filename().string();
    if (const aiTexture* t = scene.GetEmbeddedTexture(written.c_str())) {  // FBX: "*N" or an embedded file's name
      MaterialImage img;
      if (t->mHeight != 0) {  // raw ARGB8888 texels
        img.name = t->mFilename.length ? t->mFilename.C_Str() : name;
        img.width = static_cast<int>(t->mWidth);
        img.height = static_cast<int>(t->mHeight);
        const std::size_t n = std::size_t(t->mWidth) * t->mHeight;
        if (double(n) * 4 > double(kMaxMaterialImageBytes) || t->mWidth > unsigned(kMaxMaterialImageSide) ||
            t->mHeight > unsigned(kMaxMaterialImageSide)) {
          img.width = img.height = 0;
          img.error = "embedded texture of " + std::to_string(t->mWidth) + " × " + std::to_string(t->mHeight) +
                      " pixels is over the limit for texture images";
        } else {
          img.rgba8.resize(n * 4);
          for (std::size_t i = 0; i < n; ++i) {
            const aiTexel& s = t->pcData[i];
            img.rgba8[i * 4 + 0] = s.r, img.rgba8[i * 4 + 1] = s.g, img.rgba8[i * 4 + 2] = s.b;
            img.rgba8[i * 4 + 3] = s.a;
          }
          img.encoded = encode_png_rgba8(img.width, img.height, img.rgba8);
          img.mime_type = "image/png";
        }
        set.images.push_back(std::make_shared<const MaterialImage>(std::move(img)));
      } else {  // compressed file bytes (PNG, JPEG, …)
        const auto* b = reinterpret_cast<const std::uint8_t*>(t->pcData);
        set.images.push_back(std::make_shared<const MaterialImage>(decode_material_image(
            std::vector<std::uint8_t>(b, b + t->mWidth), "", name, t->mFilename.length ? t->mFilename.C_Str() : "")));
      }
      return index;
    }
    std::vector<std::uint8_t> bytes;
    try {
      const std::vector<unsigned char> read = read_model_side_file(model, written, kMaxModelTextureFileBytes);
      bytes.assign(read.begin(), read.end());
    } catch (const MeshIoError& e) {
      MaterialImage img;
      img.name = name;
      img.uri = uri;
      img.error = e.what();
      set.images.push_back(std::make_shared<const MaterialImage>(std::move(img)));
      return index;
    }
    set.images.push_back(std::make_shared<const MaterialImage>(decode_material_image(std::move(bytes), "", name, uri)));
    return index;
  }
};

TextureWrap wrap_of(aiTextureMapMode m) {
  switch (m) {
    case aiTextureMapMode_Clamp:
    case aiTextureMapMode_Decal:
      return TextureWrap::ClampToEdge;
    case aiTextureMapMode_Mirror:
      return TextureWrap::MirroredRepeat;
    default:
      return TextureWrap::Repeat;
  }
}

// The first texture of `type`, or none.
MaterialTexture texture(const aiMaterial& m, aiTextureType type, ImageTable& images) {
  MaterialTexture t;
  if (m.GetTextureCount(type) == 0) return t;
  aiString path;
  aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
  if (m.GetTexture(type, 0, &path, nullptr, nullptr, nullptr, nullptr, modes) != aiReturn_SUCCESS) return t;
  if (path.length == 0) return t;
  t.image = images.image(path.C_Str());
  t.sampler.wrap_s = wrap_of(modes[0]);
  t.sampler.wrap_t = wrap_of(modes[1]);
  return t;
}

double clamp01(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 1.0; }

// base colour RGB + the alpha of `mask`'s first channel (nearest texel): a new PNG image.
MaterialImage with_alpha_of(const MaterialImage& base, const MaterialImage& mask) {
  MaterialImage out;
  out.name = base.name + "+" + mask.name;
  out.width = base.width;
  out.height = base.height;
  out.rgba8 = base.rgba8;
  for (int y = 0; y < base.height; ++y) {
    const int my = static_cast<int>(std::int64_t(y) * mask.height / base.height);
    for (int x = 0; x < base.width; ++x) {
      const int mx = static_cast<int>(std::int64_t(x) * mask.width / base.width);
      out.rgba8[(std::size_t(y) * base.width + x) * 4 + 3] = mask.rgba8[(std::size_t(my) * mask.width + mx) * 4];
    }
  }
  out.encoded = encode_png_rgba8(out.width, out.height, out.rgba8);
  out.mime_type = "image/png";
  return out;
}

Material convert(const aiMaterial& am, ImageTable& images) {
  Material m;
  aiString name;
  if (am.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS) m.name = name.C_Str();
  aiColor4D base4;
  aiColor3D c;
  if (am.Get(AI_MATKEY_BASE_COLOR, base4) == aiReturn_SUCCESS)
    m.base_color = {clamp01(base4.r), clamp01(base4.g), clamp01(base4.b), clamp01(base4.a)};
  else if (am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == aiReturn_SUCCESS)
    m.base_color = {clamp01(c.r), clamp01(c.g), clamp01(c.b), 1.0};
  float opacity = 1.f;
  if (am.Get(AI_MATKEY_OPACITY, opacity) == aiReturn_SUCCESS && std::isfinite(opacity))
    m.base_color.w = clamp01(opacity);
  if (m.base_color.w < 1.0) m.alpha_mode = AlphaMode::Blend;

  m.base_color_texture = texture(am, aiTextureType_BASE_COLOR, images);
  if (!m.base_color_texture.present()) m.base_color_texture = texture(am, aiTextureType_DIFFUSE, images);
  const MaterialTexture alpha = texture(am, aiTextureType_OPACITY, images);
  if (alpha.present()) {
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = 0.5;
    if (alpha.image != m.base_color_texture.image) {
      const MaterialImage& mask = *images.set.images[std::size_t(alpha.image)];
      if (!m.base_color_texture.present()) {  // white, with the mask's grey as alpha
        if (mask.readable()) {
          MaterialImage white;
          white.name = "white";
          white.width = mask.width;
          white.height = mask.height;
          white.rgba8.assign(std::size_t(mask.width) * mask.height * 4, 255);
          images.set.images.push_back(std::make_shared<const MaterialImage>(with_alpha_of(white, mask)));
          m.base_color_texture = alpha;
          m.base_color_texture.image = static_cast<int>(images.set.images.size() - 1);
        } else {
          m.base_color_texture = alpha;  // unreadable: the placeholder, and its error names the file
        }
      } else {
        const MaterialImage& base = *images.set.images[std::size_t(m.base_color_texture.image)];
        if (base.readable() && mask.readable()) {
          images.set.images.push_back(std::make_shared<const MaterialImage>(with_alpha_of(base, mask)));
          m.base_color_texture.image = static_cast<int>(images.set.images.size() - 1);
        }
      }
    }
  }

  m.normal_texture = texture(am, aiTextureType_NORMALS, images);
  aiTextureType normal_type = aiTextureType_NORMALS;
  if (!m.normal_texture.present()) {
    m.normal_texture = texture(am, aiTextureType_HEIGHT, images);
    normal_type = aiTextureType_HEIGHT;
  }
  float bump = 1.f;
  if (m.normal_texture.present() && am.Get(AI_MATKEY_OBJ_BUMPMULT(normal_type, 0), bump) == aiReturn_SUCCESS &&
      std::isfinite(bump))
    m.normal_texture.scale = bump;

  if (am.Get(AI_MATKEY_COLOR_EMISSIVE, c) == aiReturn_SUCCESS) m.emissive = {clamp01(c.r), clamp01(c.g), clamp01(c.b)};
  m.emissive_texture = texture(am, aiTextureType_EMISSION_COLOR, images);
  if (!m.emissive_texture.present()) m.emissive_texture = texture(am, aiTextureType_EMISSIVE, images);
  if (m.emissive_texture.present() && m.emissive == glm::dvec3(0.0)) m.emissive = glm::dvec3(1.0);

  m.occlusion_texture = texture(am, aiTextureType_AMBIENT_OCCLUSION, images);

  float f = 0.f;
  m.metallic = am.Get(AI_MATKEY_METALLIC_FACTOR, f) == aiReturn_SUCCESS && std::isfinite(f) ? clamp01(f) : 0.0;
  if (am.Get(AI_MATKEY_ROUGHNESS_FACTOR, f) == aiReturn_SUCCESS && std::isfinite(f)) {
    m.roughness = clamp01(f);
  } else {
    aiColor3D ks(1.f, 1.f, 1.f);
    const bool has_ks = am.Get(AI_MATKEY_COLOR_SPECULAR, ks) == aiReturn_SUCCESS;
    float ns = 0.f;
    const bool has_ns = am.Get(AI_MATKEY_SHININESS, ns) == aiReturn_SUCCESS && std::isfinite(ns);
    const bool black_ks = has_ks && ks.r <= 0.f && ks.g <= 0.f && ks.b <= 0.f;
    m.roughness = has_ns && !black_ks ? 1.0 - std::sqrt(std::clamp(double(ns), 0.0, 1000.0) / 1000.0) : 1.0;
  }
  int two_sided = 0;
  if (am.Get(AI_MATKEY_TWOSIDED, two_sided) == aiReturn_SUCCESS) m.double_sided = two_sided != 0;
  return m;
}

// A material assimp made up for a format without materials: "DefaultMaterial" (STL, and meshes without one), or
// unnamed (the OFF and PLY loaders' grey), without textures. Every format that has materials names them.
bool is_assimp_default(const aiMaterial& am) {
  aiString name;
  if (am.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS && std::strcmp(name.C_Str(), AI_DEFAULT_MATERIAL_NAME) != 0)
    return false;
  for (int t = aiTextureType_NONE + 1; t <= AI_TEXTURE_TYPE_MAX; ++t)
    if (am.GetTextureCount(static_cast<aiTextureType>(t))) return false;
  return true;
}

}  // namespace

std::shared_ptr<const MaterialSet> convert_assimp_materials(const aiScene& scene, const std::vector<unsigned>& used,
                                                            const std::filesystem::path& model) {
  if (used.empty()) return nullptr;
  if (used.size() == 1 && used[0] < scene.mNumMaterials && is_assimp_default(*scene.mMaterials[used[0]]))
    return nullptr;
  auto set = std::make_shared<MaterialSet>();
  ImageTable images{scene, model, *set, {}};
  for (const unsigned index : used) {
    if (index >= scene.mNumMaterials) {
      set->materials.emplace_back();  // a mesh without a valid material: glTF's default material
      continue;
    }
    set->materials.push_back(convert(*scene.mMaterials[index], images));
  }
  // Images no texture refers to (a map_d image folded into a combined one, a map_Kd replaced by it) are dropped.
  std::vector<int> remap(set->images.size(), -1);
  std::vector<std::shared_ptr<const MaterialImage>> kept;
  for (Material& m : set->materials)
    for (MaterialTexture* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                               &m.occlusion_texture, &m.emissive_texture}) {
      if (!t->present()) continue;
      int& r = remap[std::size_t(t->image)];
      if (r < 0) {
        r = static_cast<int>(kept.size());
        kept.push_back(set->images[std::size_t(t->image)]);
      }
      t->image = r;
    }
  set->images = std::move(kept);
  return set;
}

}  // namespace trispline::core
