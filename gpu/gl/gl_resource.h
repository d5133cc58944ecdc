// trispline::gpu RAII handles for GL objects: move-only, deleted on destruction (the creating context, or one
// sharing with it, must be current then). Plain GL 4.3 (glGen*/glDelete*), no direct state access, so a 4.3
// fallback context works the same.
//   Buffer, VertexArray, Texture, Renderbuffer, Framebuffer, Query
#pragma once

#include <epoxy/gl.h>

#include <utility>

namespace trispline::gpu {

enum class GlKind { buffer, vertex_array, texture, renderbuffer, framebuffer, query };

namespace detail {
GLuint gen_gl_object(GlKind kind);
void delete_gl_object(GlKind kind, GLuint id);
}  // namespace detail

template <GlKind Kind>
class GlHandle {
 public:
  GlHandle() = default;  // empty (id() == 0)
  static GlHandle create() { return GlHandle(detail::gen_gl_object(Kind)); }
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) detail::delete_gl_object(Kind, id_);
    id_ = 0;
  }

 private:
  explicit GlHandle(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

using Buffer = GlHandle<GlKind::buffer>;
using VertexArray = GlHandle<GlKind::vertex_array>;
using Texture = GlHandle<GlKind::texture>;
using Renderbuffer = GlHandle<GlKind::renderbuffer>;
using Framebuffer = GlHandle<GlKind::framebuffer>;
using Query = GlHandle<GlKind::query>;

// Surfaceless EGL has no default framebuffer, yet a draw — even one with GL_RASTERIZER_DISCARD, for transform
// feedback — needs a complete draw framebuffer. When the bound one is incomplete, binds `fbo` (a 1 × 1 RGBA8
// framebuffer with renderbuffer `rb`, made on first use and kept by the caller) and returns the previous binding;
// returns −1 and binds nothing when the bound one is complete. Pass the result to restore_draw_framebuffer.
GLint bind_complete_draw_framebuffer(Framebuffer& fbo, Renderbuffer& rb);
void restore_draw_framebuffer(GLint previous);  // no-op for −1

// Feeds vertex attribute `location` of the bound vertex array from `buffer`: `components` tightly packed floats a
// vertex (the buffer stays bound to GL_ARRAY_BUFFER).
void float_attribute(GLuint location, GLuint buffer, GLint components);

}  // namespace trispline::gpu
