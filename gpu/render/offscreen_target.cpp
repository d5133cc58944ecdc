// OffscreenTarget (declared in gpu/render/renderer.h): an FBO with RGBA8 colour and DEPTH24_STENCIL8, optionally
// multisampled and resolved by a blit into a single-sample FBO whose colour is a texture.
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "gpu/gl/gl_resource.h"
#include "gpu/render/renderer.h"

namespace trispline::gpu {

struct OffscreenTarget::Impl {
  int width = 0, height = 0, samples = 1;
  Framebuffer msaa_fbo, resolve_fbo;
  Renderbuffer msaa_color, depth_stencil;
  Texture color;  // single-sample colour (the resolve target; the draw target too when samples == 1)
};

namespace {

void check_complete(const char* what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  char buf[96];
  std::snprintf(buf, sizeof buf, "OffscreenTarget: %s framebuffer incomplete (status 0x%x)", what, unsigned(status));
  throw std::runtime_error(buf);
}

}  // namespace

OffscreenTarget::OffscreenTarget(int width, int height, int samples) : impl_(std::make_unique<Impl>()) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("OffscreenTarget: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  Impl& d = *impl_;
  d.width = width;
  d.height = height;
  d.samples = std::clamp(samples, 1, std::max(1, int(max_samples)));

  GLint prev_fbo = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev_fbo);
  d.color = Texture::create();
  glBindTexture(GL_TEXTURE_2D, d.color.id());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glBindTexture(GL_TEXTURE_2D, 0);
  d.depth_stencil = Renderbuffer::create();
  glBindRenderbuffer(GL_RENDERBUFFER, d.depth_stencil.id());
  if (d.samples > 1)
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, d.samples, GL_DEPTH24_STENCIL8, width, height);
  else
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);

  d.resolve_fbo = Framebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, d.resolve_fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, d.color.id(), 0);
  if (d.samples == 1)
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, d.depth_stencil.id());
  check_complete("resolve");

  if (d.samples > 1) {
    d.msaa_color = Renderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, d.msaa_color.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, d.samples, GL_RGBA8, width, height);
    d.msaa_fbo = Framebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, d.msaa_fbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, d.msaa_color.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, d.depth_stencil.id());
    check_complete("multisampled");
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(prev_fbo));
}

OffscreenTarget::~OffscreenTarget() = default;

void OffscreenTarget::bind() {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer());
  glViewport(0, 0, impl_->width, impl_->height);
}

int OffscreenTarget::width() const { return impl_->width; }
int OffscreenTarget::height() const { return impl_->height; }
int OffscreenTarget::samples() const { return impl_->samples; }

GLuint OffscreenTarget::framebuffer() const {
  return impl_->samples > 1 ? impl_->msaa_fbo.id() : impl_->resolve_fbo.id();
}

GLuint OffscreenTarget::resolve() {
  const Impl& d = *impl_;
  if (d.samples > 1) {
    GLint prev_read = 0, prev_draw = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_read);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_draw);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, d.msaa_fbo.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d.resolve_fbo.id());
    glBlitFramebuffer(0, 0, d.width, d.height, 0, 0, d.width, d.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(prev_read));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(prev_draw));
  }
  return d.color.id();
}

std::vector<unsigned char> OffscreenTarget::read_rgba() {
  resolve();
  const Impl& d = *impl_;
  const std::size_t row = std::size_t(d.width) * 4;
  std::vector<unsigned char> bottom_up(row * std::size_t(d.height));
  GLint prev_read = 0, prev_pack = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_read);
  glGetIntegerv(GL_PACK_ALIGNMENT, &prev_pack);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, d.resolve_fbo.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glReadPixels(0, 0, d.width, d.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  glPixelStorei(GL_PACK_ALIGNMENT, prev_pack);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(prev_read));
  std::vector<unsigned char> out(bottom_up.size());
  for (int y = 0; y < d.height; ++y)
    std::copy_n(bottom_up.begin() + std::ptrdiff_t(row * std::size_t(d.height - 1 - y)), row,
                out.begin() + std::ptrdiff_t(row * std::size_t(y)));
  return out;
}

}  // namespace trispline::gpu
