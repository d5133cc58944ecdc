#include "gpu/gl_resource.h"

namespace trispline::gpu::detail {

GLuint gen_gl_object(GlKind kind) {
  GLuint id = 0;
  switch (kind) {
    case GlKind::buffer:
      glGenBuffers(1, &id);
      break;
    case GlKind::vertex_array:
      glGenVertexArrays(1, &id);
      break;
    case GlKind::texture:
      glGenTextures(1, &id);
      break;
    case GlKind::renderbuffer:
      glGenRenderbuffers(1, &id);
      break;
    case GlKind::framebuffer:
      glGenFramebuffers(1, &id);
      break;
    case GlKind::query:
      glGenQueries(1, &id);
      break;
  }
  return id;
}

void delete_gl_object(GlKind kind, GLuint id) {
  switch (kind) {
    case GlKind::buffer:
      glDeleteBuffers(1, &id);
      break;
    case GlKind::vertex_array:
      glDeleteVertexArrays(1, &id);
      break;
    case GlKind::texture:
      glDeleteTextures(1, &id);
      break;
    case GlKind::renderbuffer:
      glDeleteRenderbuffers(1, &id);
      break;
    case GlKind::framebuffer:
      glDeleteFramebuffers(1, &id);
      break;
    case GlKind::query:
      glDeleteQueries(1, &id);
      break;
  }
}

}  // namespace trispline::gpu::detail
