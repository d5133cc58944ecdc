#include "gpu/gl/gl_resource.h"

#include <iterator>

namespace trispline::gpu::detail {

namespace {

// The glGen* / glDelete* pair of each GlKind, in the enum's order.
struct GlObjectCalls {
  void (*gen)(GLuint* id);
  void (*del)(GLuint id);
};
constexpr GlObjectCalls kGlObjectCalls[] = {
    {[](GLuint* id) { glGenBuffers(1, id); }, [](GLuint id) { glDeleteBuffers(1, &id); }},
    {[](GLuint* id) { glGenVertexArrays(1, id); }, [](GLuint id) { glDeleteVertexArrays(1, &id); }},
    {[](GLuint* id) { glGenTextures(1, id); }, [](GLuint id) { glDeleteTextures(1, &id); }},
    {[](GLuint* id) { glGenRenderbuffers(1, id); }, [](GLuint id) { glDeleteRenderbuffers(1, &id); }},
    {[](GLuint* id) { glGenFramebuffers(1, id); }, [](GLuint id) { glDeleteFramebuffers(1, &id); }},
    {[](GLuint* id) { glGenQueries(1, id); }, [](GLuint id) { glDeleteQueries(1, &id); }},
};
static_assert(std::size(kGlObjectCalls) == std::size_t(GlKind::query) + 1, "one entry per GlKind");

}  // namespace

GLuint gen_gl_object(GlKind kind) {
  GLuint id = 0;
  kGlObjectCalls[std::size_t(kind)].gen(&id);
  return id;
}

void delete_gl_object(GlKind kind, GLuint id) { kGlObjectCalls[std::size_t(kind)].del(id); }

}  // namespace trispline::gpu::detail

namespace trispline::gpu {

void float_attribute(GLuint location, GLuint buffer, GLint components) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, GLsizei(components * sizeof(float)), nullptr);
}

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
