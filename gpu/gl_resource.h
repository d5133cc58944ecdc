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

}  // namespace trispline::gpu
