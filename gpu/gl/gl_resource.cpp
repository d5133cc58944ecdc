#include "gpu/gl/gl_resource.h"

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

namespace trispline::gpu {

GLint bind_complete_draw_framebuffer(Framebuffer& fbo, Renderbuffer& rb) {
  if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return -1;
  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  if (!fbo) {
    fbo = Framebuffer::create();
    rb = Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, rb.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo.id());
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb.id());
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo.id());
  return previous;
}

void restore_draw_framebuffer(GLint previous) {
  if (previous >= 0) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previous));
}

}  // namespace trispline::gpu
