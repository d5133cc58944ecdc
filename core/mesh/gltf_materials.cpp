// glTF materials ↔ MaterialSet. See gltf_materials.h.
#include "core/mesh/gltf_materials.h"

#include <algorithm>

#include "core/mesh/file_check.h"
#include "core/mesh/gltf_model.h"
#include "core/mesh/gltf_read.h"
#include "core/mesh/material_image.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/path_quote.h"

namespace trispline::core::gltf_materials {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

TextureWrap wrap_of(int v) {
  if (v == static_cast<int>(TextureWrap::ClampToEdge)) return TextureWrap::ClampToEdge;
  if (v == static_cast<int>(TextureWrap::MirroredRepeat)) return TextureWrap::MirroredRepeat;
  return TextureWrap::Repeat;
}

TextureFilter filter_of(int v) {
  switch (v) {
    case 9728:
    case 9729:
    case 9984:
    case 9985:
    case 9986:
    case 9987:
      return static_cast<TextureFilter>(v);
    default:
      return TextureFilter::Unset;
  }
}

class Reader {
 public:
  Reader(const tinygltf::Model& model, const fs::path& path, ReadMaterials& out)
      : model_(model), path_(path), out_(out), image_slot_(model.images.size(), -1) {}

  // texture `index` with `texcoord` (a TextureInfo) → MaterialTexture; `scale` for normal / occlusion.
  MaterialTexture texture(int index, int texcoord, double scale, const std::string& where) {
    MaterialTexture t;
    t.scale = scale;
    t.texcoord = texcoord;
    if (index < 0) return t;
    if (index >= static_cast<int>(model_.textures.size()))
      throw MeshIoError(quoted(path_) + ": " + where + " refers to texture " + std::to_string(index) +
                        ", which does not exist (the file has " + std::to_string(model_.textures.size()) + ")");
    const tinygltf::Texture& tex = model_.textures[index];
    if (tex.sampler >= static_cast<int>(model_.samplers.size()))
      throw MeshIoError(quoted(path_) + ": texture " + std::to_string(index) + " refers to sampler " +
                        std::to_string(tex.sampler) + ", which does not exist");
    if (tex.sampler >= 0) {
      const tinygltf::Sampler& s = model_.samplers[tex.sampler];
      t.sampler.wrap_s = wrap_of(s.wrapS);
      t.sampler.wrap_t = wrap_of(s.wrapT);
      t.sampler.mag_filter = filter_of(s.magFilter);
      t.sampler.min_filter = filter_of(s.minFilter);
    }
    if (tex.source < 0) {  // e.g. only KHR_texture_basisu / EXT_texture_webp sources: no image we can read
      out_.warnings.push_back("texture " + std::to_string(index) + " has no PNG or JPEG source image; left out");
      return t;
    }
    if (tex.source >= static_cast<int>(model_.images.size()))
      throw MeshIoError(quoted(path_) + ": texture " + std::to_string(index) + " refers to image " +
                        std::to_string(tex.source) + ", which does not exist (the file has " +
                        std::to_string(model_.images.size()) + ")");
    t.image = image(tex.source);
    return t;
  }

 private:
  int image(int index) {
    int& slot = image_slot_[index];
    if (slot >= 0) return slot;
    const tinygltf::Image& im = model_.images[index];
    std::vector<std::uint8_t> bytes;
    std::string error;
    const bool external = im.bufferView < 0 && !im.uri.empty() && im.image.empty();
    try {
      if (external) {
        bytes = gltf_read::external_image_bytes(path_, im.uri);
      } else {
        bytes = gltf_read::image_bytes(model_, index, path_);
        if (bytes.size() > gltf_read::kMaxImageFileBytes)
          error = "its " + format_bytes(bytes.size()) + " are over the " + format_bytes(gltf_read::kMaxImageFileBytes) +
                  " limit for texture images";
      }
    } catch (const MeshIoError& e) {
      error = e.what();
    }
    const std::string name = !im.name.empty() ? im.name : external ? fs::path(im.uri).filename().string() : "";
    MaterialImage decoded;
    if (error.empty()) {
      const std::uint64_t left = kMaxFileImageBytes - std::min(kMaxFileImageBytes, decoded_bytes_);
      decoded = decode_material_image(std::move(bytes), im.mimeType, name, external ? im.uri : "",
                                      std::min(kMaxMaterialImageBytes, left));
      if (!decoded.error.empty() && left < kMaxMaterialImageBytes && decoded.width == 0)
        decoded.error += " (the file's images together may decode to " + format_bytes(kMaxFileImageBytes) + ")";
    } else {
      decoded.name = name;
      decoded.uri = external ? im.uri : "";
      decoded.error = error;
    }
    decoded_bytes_ += decoded.rgba8.size();
    if (!decoded.error.empty())
      out_.warnings.push_back("image " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')") + ": " +
                              decoded.error);
    out_.set.images.push_back(std::make_shared<const MaterialImage>(std::move(decoded)));
    slot = static_cast<int>(out_.set.images.size()) - 1;
    return slot;
  }

  const tinygltf::Model& model_;
  const fs::path& path_;
  ReadMaterials& out_;
  std::vector<int> image_slot_;  // glTF image → set image
  std::uint64_t decoded_bytes_ = 0;
};

}  // namespace

Material default_material() { return Material{}; }

ReadMaterials read_gltf_materials(const tinygltf::Model& model, const fs::path& path) {
  ReadMaterials out;
  if (model.materials.size() > kMaxMaterialsPerMesh)
    throw MeshIoError(quoted(path) + ": " + std::to_string(model.materials.size()) + " materials, more than the " +
                      std::to_string(kMaxMaterialsPerMesh) + " an object may have");
  Reader reader(model, path, out);
  out.slot.assign(model.materials.size(), -1);
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& gm = model.materials[i];
    if (ends_with(gm.name, ".inside")) continue;  // write_glb's cut surfaces: kMaterialInside
    const std::string where = "material " + std::to_string(i);
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name;
    if (pbr.baseColorFactor.size() == 4)
      m.base_color = {pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]};
    m.base_color_texture = reader.texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, 1.0, where);
    m.metallic = pbr.metallicFactor;
    m.roughness = pbr.roughnessFactor;
    m.metallic_roughness_texture =
        reader.texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, 1.0, where);
    m.normal_texture = reader.texture(gm.normalTexture.index, gm.normalTexture.texCoord, gm.normalTexture.scale, where);
    m.occlusion_texture =
        reader.texture(gm.occlusionTexture.index, gm.occlusionTexture.texCoord, gm.occlusionTexture.strength, where);
    if (gm.emissiveFactor.size() == 3) m.emissive = {gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]};
    m.emissive_texture = reader.texture(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, 1.0, where);
    m.alpha_mode = gm.alphaMode == "MASK"    ? AlphaMode::Mask
                   : gm.alphaMode == "BLEND" ? AlphaMode::Blend
                                             : AlphaMode::Opaque;
    m.alpha_cutoff = gm.alphaCutoff;
    m.double_sided = gm.doubleSided;
    out.slot[i] = static_cast<int>(out.set.materials.size());
    out.set.materials.push_back(std::move(m));
  }
  return out;
}

// ---- writing --------------------------------------------------------------------------------------------------------

const std::vector<int>& GltfMaterialWriter::materials(const std::shared_ptr<const MaterialSet>& set) {
  const auto known = sets_.find(set.get());
  if (known != sets_.end()) return known->second;
  keep_.push_back(set);
  std::vector<int> out;
  for (const Material& m : set->materials) {
    tinygltf::Material gm;
    gm.name = m.name;
    auto& pbr = gm.pbrMetallicRoughness;
    pbr.baseColorFactor = {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]};
    pbr.metallicFactor = m.metallic;
    pbr.roughnessFactor = m.roughness;
    pbr.baseColorTexture.index = texture(*set, m.base_color_texture);
    pbr.baseColorTexture.texCoord = m.base_color_texture.texcoord;
    pbr.metallicRoughnessTexture.index = texture(*set, m.metallic_roughness_texture);
    pbr.metallicRoughnessTexture.texCoord = m.metallic_roughness_texture.texcoord;
    gm.normalTexture.index = texture(*set, m.normal_texture);
    gm.normalTexture.texCoord = m.normal_texture.texcoord;
    gm.normalTexture.scale = m.normal_texture.scale;
    gm.occlusionTexture.index = texture(*set, m.occlusion_texture);
    gm.occlusionTexture.texCoord = m.occlusion_texture.texcoord;
    gm.occlusionTexture.strength = m.occlusion_texture.scale;
    gm.emissiveFactor = {m.emissive[0], m.emissive[1], m.emissive[2]};
    gm.emissiveTexture.index = texture(*set, m.emissive_texture);
    gm.emissiveTexture.texCoord = m.emissive_texture.texcoord;
    gm.alphaMode = m.alpha_mode == AlphaMode::Mask ? "MASK" : m.alpha_mode == AlphaMode::Blend ? "BLEND" : "OPAQUE";
    gm.alphaCutoff = m.alpha_cutoff;
    gm.doubleSided = m.double_sided;
    model_.materials.push_back(gm);
    out.push_back(static_cast<int>(model_.materials.size()) - 1);
  }
  return sets_.emplace(set.get(), std::move(out)).first->second;
}

int GltfMaterialWriter::texture(const MaterialSet& set, const MaterialTexture& t) {
  if (!t.present() || t.image >= static_cast<int>(set.images.size()) || !set.images[t.image]) return -1;
  const int img = image(set.images[t.image]);
  if (img < 0) return -1;
  const int smp = sampler(t.sampler);
  const auto [it, fresh] = textures_.try_emplace({img, smp}, static_cast<int>(model_.textures.size()));
  if (fresh) {
    tinygltf::Texture tex;
    tex.source = img;
    tex.sampler = smp;
    model_.textures.push_back(tex);
  }
  return it->second;
}

int GltfMaterialWriter::image(const std::shared_ptr<const MaterialImage>& image) {
  const auto known = images_.find(image.get());
  if (known != images_.end()) return known->second;
  std::pair<std::vector<std::uint8_t>, std::string> encoded;
  try {
    encoded = gltf_image_bytes(*image);
  } catch (const std::exception&) {
    encoded = {};  // a picture the PNG encoder refuses: the material is written without it
  }
  const auto& [bytes, mime] = encoded;
  int index = -1;
  if (!bytes.empty()) {
    tinygltf::Image im;
    im.name = image->name;
    im.mimeType = mime;
    im.bufferView = gltf_model::add_view(model_, bytes.data(), bytes.size(), 0);
    model_.images.push_back(im);
    index = static_cast<int>(model_.images.size()) - 1;
  }
  images_.emplace(image.get(), index);
  return index;
}

int GltfMaterialWriter::sampler(const TextureSampler& s) {
  for (const auto& [known, index] : samplers_)
    if (known == s) return index;
  tinygltf::Sampler gs;
  gs.wrapS = static_cast<int>(s.wrap_s);
  gs.wrapT = static_cast<int>(s.wrap_t);
  gs.magFilter = s.mag_filter == TextureFilter::Unset ? -1 : static_cast<int>(s.mag_filter);
  gs.minFilter = s.min_filter == TextureFilter::Unset ? -1 : static_cast<int>(s.min_filter);
  model_.samplers.push_back(gs);
  samplers_.emplace_back(s, static_cast<int>(model_.samplers.size()) - 1);
  return samplers_.back().second;
}

}  // namespace trispline::core::gltf_materials
