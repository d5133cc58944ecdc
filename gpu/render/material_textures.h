// trispline::gpu::MaterialTextures — the GL textures and samplers of objects' materials (core/mesh/material.h) for
// Material shading: one mipmapped texture per image and colour space, cached on the image's identity (the
// shared_ptr's address, held so it cannot be reused), one sampler object per TextureSampler value.
//
// Colour spaces (glTF 2.0 §3.9.2, §3.9.5): base colour and emissive images are sRGB-encoded (GL_SRGB8_ALPHA8, decoded
// by the sampler); metallic-roughness, normal and occlusion images are linear (GL_RGBA8). An unreadable image
// (MaterialImage::readable() false: a missing or undecodable file) samples as Blender's magenta placeholder.
// Absent textures sample as white (or the flat normal (0.5, 0.5, 1)), so the shader multiplies unconditionally.
// Internal to gpu/ (the renderer's Material shading). Needs a current GL context.
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <memory>
#include <unordered_map>

#include "core/mesh/material.h"
#include "core/scene/scene.h"
#include "gpu/gl/gl_resource.h"
#include "gpu/gl/shader_program.h"

namespace trispline::gpu {

enum class TextureColorSpace { srgb, linear };

class MaterialTextures {
 public:
  MaterialTextures() = default;
  ~MaterialTextures();
  MaterialTextures(const MaterialTextures&) = delete;
  MaterialTextures& operator=(const MaterialTextures&) = delete;

  // Texture units 0..4 hold base colour, metallic-roughness, normal, occlusion, emissive; binds the textures and
  // samplers of `m` (its images from `set`; an index outside set.images counts as unreadable) to them. The program
  // that draws sets uniforms with set_uniforms.
  void bind(const core::Material& m, const core::MaterialSet& set);
  // Sets the MATERIAL variant's uniforms of `m` on `p` (in use): factors, alpha mode, sampler units.
  static void set_uniforms(const core::Material& m, const ShaderProgram& p);
  // Unbinds the sampler objects from units 0..4 and leaves unit 0 active (others, e.g. ImGui, use texture state).
  void unbind();

  // The texture of `image` in `space` (uploaded on first use); the placeholder when it is unreadable or larger than
  // GL_MAX_TEXTURE_SIZE.
  GLuint texture(const std::shared_ptr<const core::MaterialImage>& image, TextureColorSpace space);
  GLuint sampler(const core::TextureSampler& s);
  GLuint placeholder();  // 1×1 magenta (1, 0, 1, 1)
  GLuint white();        // 1×1 (1, 1, 1, 1)
  GLuint flat_normal();  // 1×1 (0.5, 0.5, 1, 1): the unperturbed tangent-space normal

  // Drops textures of images no object of `scene` refers to any more.
  void release_unused(const core::Scene& scene);
  std::size_t cached() const { return textures_.size(); }  // image textures held
  int uploads() const { return uploads_; }                 // image textures uploaded so far

 private:
  struct Key {
    const core::MaterialImage* image;
    TextureColorSpace space;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<const void*>()(k.image) ^ (k.space == TextureColorSpace::srgb ? 0x9e3779b9u : 0u);
    }
  };
  struct Cached {
    std::shared_ptr<const core::MaterialImage> image;  // held so the address cannot be reused
    Texture texture;
  };
  GLuint texture_or_default(const core::MaterialTexture& t, const core::MaterialSet& set, TextureColorSpace space,
                            GLuint fallback);
  std::unordered_map<Key, Cached, KeyHash> textures_;
  std::unordered_map<std::uint64_t, GLuint> samplers_;
  Texture placeholder_, white_, flat_normal_;
  int uploads_ = 0;
};

}  // namespace trispline::gpu
