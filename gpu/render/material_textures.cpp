#include "gpu/render/material_textures.h"

#include <algorithm>
#include <unordered_set>

namespace trispline::gpu {
namespace {

constexpr int kUnits = 5;  // base colour, metallic-roughness, normal, occlusion, emissive

Texture solid_texture(std::uint8_t r, std::uint8_t g, std::uint8_t b, GLenum internal_format) {
  Texture t = Texture::create();
  const std::uint8_t px[4] = {r, g, b, 255};
  glBindTexture(GL_TEXTURE_2D, t.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, 1, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  return t;
}

GLint min_filter(core::TextureFilter f) {
  switch (f) {
    case core::TextureFilter::Nearest:
    case core::TextureFilter::Linear:
    case core::TextureFilter::NearestMipmapNearest:
    case core::TextureFilter::LinearMipmapNearest:
    case core::TextureFilter::NearestMipmapLinear:
    case core::TextureFilter::LinearMipmapLinear:
      return GLint(f);
    case core::TextureFilter::Unset:
      break;
  }
  return GL_LINEAR_MIPMAP_LINEAR;
}

GLint mag_filter(core::TextureFilter f) { return f == core::TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR; }

GLint wrap(core::TextureWrap w) {
  switch (w) {
    case core::TextureWrap::ClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case core::TextureWrap::MirroredRepeat:
      return GL_MIRRORED_REPEAT;
    case core::TextureWrap::Repeat:
      break;
  }
  return GL_REPEAT;
}

}  // namespace

MaterialTextures::~MaterialTextures() {
  for (const auto& kv : samplers_) glDeleteSamplers(1, &kv.second);
}

GLuint MaterialTextures::placeholder() {
  if (!placeholder_) placeholder_ = solid_texture(255, 0, 255, GL_RGBA8);
  return placeholder_.id();
}

GLuint MaterialTextures::white() {
  if (!white_) white_ = solid_texture(255, 255, 255, GL_RGBA8);
  return white_.id();
}

GLuint MaterialTextures::flat_normal() {
  if (!flat_normal_) flat_normal_ = solid_texture(128, 128, 255, GL_RGBA8);
  return flat_normal_.id();
}

GLuint MaterialTextures::texture(const std::shared_ptr<const core::MaterialImage>& image, TextureColorSpace space) {
  if (!image || !image->readable() || image->rgba8.size() != std::size_t(image->width) * std::size_t(image->height) * 4)
    return placeholder();
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (image->width > max_size || image->height > max_size) return placeholder();
  auto [it, inserted] = textures_.try_emplace(Key{image.get(), space});
  if (!inserted) return it->second.texture.id();
  it->second.image = image;
  it->second.texture = Texture::create();
  int levels = 1;
  while ((std::max(image->width, image->height) >> levels) > 0) ++levels;
  glBindTexture(GL_TEXTURE_2D, it->second.texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexStorage2D(GL_TEXTURE_2D, levels, space == TextureColorSpace::srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image->width,
                 image->height);
  // Rows top to bottom go to t = 0 upwards: glTF's uv (0,0) is the image's top-left corner, sampled unflipped.
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image->width, image->height, GL_RGBA, GL_UNSIGNED_BYTE, image->rgba8.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  ++uploads_;
  return it->second.texture.id();
}

GLuint MaterialTextures::sampler(const core::TextureSampler& s) {
  const std::uint64_t key = (std::uint64_t(std::uint16_t(s.wrap_s)) << 48) |
                            (std::uint64_t(std::uint16_t(s.wrap_t)) << 32) |
                            (std::uint64_t(std::uint16_t(s.mag_filter)) << 16) | std::uint16_t(s.min_filter);
  auto [it, inserted] = samplers_.try_emplace(key, 0);
  if (!inserted) return it->second;
  glGenSamplers(1, &it->second);
  const GLuint id = it->second;
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, wrap(s.wrap_s));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, wrap(s.wrap_t));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, mag_filter(s.mag_filter));
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, min_filter(s.min_filter));
  return id;
}

GLuint MaterialTextures::texture_or_default(const core::MaterialTexture& t, const core::MaterialSet& set,
                                            TextureColorSpace space, GLuint fallback) {
  if (!t.present()) return fallback;
  if (std::size_t(t.image) >= set.images.size()) return placeholder();
  return texture(set.images[std::size_t(t.image)], space);
}

void MaterialTextures::bind(const core::Material& m, const core::MaterialSet& set) {
  const core::MaterialTexture* slots[kUnits] = {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                                &m.occlusion_texture, &m.emissive_texture};
  const TextureColorSpace spaces[kUnits] = {TextureColorSpace::srgb, TextureColorSpace::linear,
                                            TextureColorSpace::linear, TextureColorSpace::linear,
                                            TextureColorSpace::srgb};
  // Every texture is resolved (created and uploaded on first use, which binds it on the active unit) before any
  // unit is bound, so no upload replaces a unit's binding.
  GLuint tex[kUnits];
  for (int u = 0; u < kUnits; ++u)
    tex[u] = texture_or_default(*slots[u], set, spaces[u], u == 2 ? flat_normal() : white());
  for (int u = 0; u < kUnits; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glBindTexture(GL_TEXTURE_2D, tex[u]);
    glBindSampler(GLuint(u), sampler(slots[u]->present() ? slots[u]->sampler : core::TextureSampler{}));
  }
  glActiveTexture(GL_TEXTURE0);
}

void MaterialTextures::set_uniforms(const core::Material& m, const ShaderProgram& p) {
  p.set("u_base_tex", 0);
  p.set("u_mr_tex", 1);
  p.set("u_normal_tex", 2);
  p.set("u_occlusion_tex", 3);
  p.set("u_emissive_tex", 4);
  p.set("u_base_color", glm::vec4(m.base_color));
  p.set("u_metallic", float(m.metallic));
  p.set("u_roughness", float(m.roughness));
  p.set("u_has_normal_tex", m.normal_texture.present() ? 1 : 0);
  p.set("u_normal_scale", float(m.normal_texture.scale));
  p.set("u_occlusion_strength", m.occlusion_texture.present() ? float(m.occlusion_texture.scale) : 0.0f);
  p.set("u_emissive", glm::vec3(m.emissive));
  p.set("u_alpha_mode", m.alpha_mode == core::AlphaMode::Mask ? 1 : m.alpha_mode == core::AlphaMode::Blend ? 2 : 0);
  p.set("u_alpha_cutoff", float(m.alpha_cutoff));
}

void MaterialTextures::unbind() {
  for (int u = 0; u < kUnits; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindSampler(GLuint(u), 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

void MaterialTextures::release_unused(const core::Scene& scene) {
  if (textures_.empty()) return;
  std::unordered_set<const core::MaterialImage*> live;
  for (const core::SceneObject& o : scene.objects()) {
    if (o.materials)
      for (const auto& image : o.materials->images) live.insert(image.get());
    if (o.inside_texture) live.insert(o.inside_texture.get());  // textured caps (object.inside)
    for (const auto& layer : o.ddm_layers)                      // texture-mapped tiles
      if (layer)
        for (const core::DdmTile& t : layer->tiles)
          if (t.materials)
            for (const auto& image : t.materials->images) live.insert(image.get());
  }
  std::erase_if(textures_, [&](const auto& kv) { return !live.count(kv.first.image); });
}

}  // namespace trispline::gpu
