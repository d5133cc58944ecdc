// VolumeIsoRenderer: GLSL ray casting of a VolumeSpline's iso-surface. See volume_gl.h; the shader is
// shaders/volume_iso.frag.glsl (with volume_iso.vert.glsl for the box).
#include "gpu/eval/volume_gl.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/volume/iso_raycast.h"
#include "core/volume/volume_dvr.h"
#include "gpu/eval/ffd_gl_lattice.h"

namespace trispline::gpu {
namespace {

constexpr GLuint kControlsUnit = 0, kBricksUnit = 1;  // layout(binding) of the two samplers

glm::mat4 to_float(const glm::dmat4& m) { return glm::mat4(m); }

void set_ivec3(const ShaderProgram& p, const char* name, const std::array<int, 3>& v) {
  glUniform3i(p.uniform(name), v[0], v[1], v[2]);
}

Texture make_texture_3d(GLenum internal, GLenum format, int nx, int ny, int nz, const void* data,
                        GLenum filter = GL_NEAREST) {
  Texture t = Texture::create();
  glBindTexture(GL_TEXTURE_3D, t.id());
  glTexStorage3D(GL_TEXTURE_3D, 1, internal, nx, ny, nz);
  GLint prev_align = 4;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &prev_align);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, nx, ny, nz, format, GL_FLOAT, data);
  glPixelStorei(GL_UNPACK_ALIGNMENT, prev_align);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GLint(filter));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GLint(filter));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_3D, 0);
  return t;
}

Texture make_texture_2d(GLenum internal, int w, int h) {
  Texture t = Texture::create();
  glBindTexture(GL_TEXTURE_2D, t.id());
  glTexStorage2D(GL_TEXTURE_2D, 1, internal, w, h);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  return t;
}

// GL state draw() changes, restored on scope exit (also when a throw leaves it). The program is not restored: the
// caller's may have been deleted while in use, and every GL class here sets its program before drawing.
class DrawStateGuard {
 public:
  DrawStateGuard() {
    cull_ = glIsEnabled(GL_CULL_FACE);
    depth_ = glIsEnabled(GL_DEPTH_TEST);
    glGetIntegerv(GL_CULL_FACE_MODE, &cull_mode_);
    glGetIntegerv(GL_FRONT_FACE, &front_face_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_);
    for (GLuint u : {kControlsUnit, kBricksUnit}) {
      glActiveTexture(GL_TEXTURE0 + u);
      glGetIntegerv(GL_TEXTURE_BINDING_3D, &tex_[u]);
    }
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
  }
  ~DrawStateGuard() {
    cull_ ? glEnable(GL_CULL_FACE) : glDisable(GL_CULL_FACE);
    depth_ ? glEnable(GL_DEPTH_TEST) : glDisable(GL_DEPTH_TEST);
    glCullFace(GLenum(cull_mode_));
    glFrontFace(GLenum(front_face_));
    for (GLuint u : {kControlsUnit, kBricksUnit}) {
      glActiveTexture(GL_TEXTURE0 + u);
      glBindTexture(GL_TEXTURE_3D, glIsTexture(GLuint(tex_[u])) ? GLuint(tex_[u]) : 0);
    }
    glActiveTexture(GLenum(active_));
    glBindVertexArray(glIsVertexArray(GLuint(vao_)) ? GLuint(vao_) : 0);
  }
  DrawStateGuard(const DrawStateGuard&) = delete;
  DrawStateGuard& operator=(const DrawStateGuard&) = delete;

 private:
  GLboolean cull_ = GL_FALSE, depth_ = GL_FALSE;
  GLint cull_mode_ = GL_BACK, front_face_ = GL_CCW, active_ = GL_TEXTURE0, vao_ = 0;
  GLint tex_[2] = {0, 0};
};

}  // namespace

std::size_t IsoHitReadback::hit_count() const {
  std::size_t n = 0;
  for (unsigned char h : hit) n += h != 0;
  return n;
}

VolumeIsoRenderer::VolumeIsoRenderer(std::shared_ptr<FfdProgramCache> programs)
    : programs_(programs ? std::move(programs) : std::make_shared<FfdProgramCache>()),
      empty_vao_(VertexArray::create()) {}

VolumeIsoRenderer::~VolumeIsoRenderer() = default;

void VolumeIsoRenderer::set_volume(const core::VolumeSpline& spline, int brick) {
  const std::array<int, 3>& n = spline.dims();
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_size);
  for (int a = 0; a < 3; ++a)
    if (n[a] > max_size)
      throw std::invalid_argument("VolumeIsoRenderer: volume of " + std::to_string(n[0]) + "x" + std::to_string(n[1]) +
                                  "x" + std::to_string(n[2]) + " exceeds GL_MAX_3D_TEXTURE_SIZE " +
                                  std::to_string(max_size));
  const core::VolumeRangeGrid grid = core::build_volume_range_grid(spline, brick);  // throws for brick < 1
  std::vector<glm::vec4> bounds(grid.range.size());
  for (std::size_t i = 0; i < bounds.size(); ++i) bounds[i] = glm::vec4(grid.range[i], grid.slope[i], 0.0f);
  check_gl_error("VolumeIsoRenderer: before upload");
  // GL_LINEAR for the march's fast values (textureLod); texelFetch, the exact path, ignores the filter.
  Texture controls = make_texture_3d(GL_R32F, GL_RED, n[0], n[1], n[2], spline.control_points().data(), GL_LINEAR);
  Texture bricks = make_texture_3d(GL_RGBA32F, GL_RGBA, grid.dims[0], grid.dims[1], grid.dims[2], bounds.data());
  check_gl_error("VolumeIsoRenderer: volume upload");
  controls_ = std::move(controls);
  bricks_ = std::move(bricks);
  dims_ = n;
  brick_dims_ = grid.dims;
  brick_ = grid.brick;
  order_ = spline.order();
  index_to_world_ = spline.index_to_world();
  world_to_index_ = spline.world_to_index();
  for (int c = 0; c < 3; ++c) {
    glm::dvec3 e(0.0);
    e[c] = 1.0;
    gradient_to_world_[c] = spline.world_gradient(e);
  }
  ++uploads_;
}

void VolumeIsoRenderer::set_step(double step_index) {
  if (!(step_index > 0.0 && step_index <= 1.0))
    throw std::invalid_argument("VolumeIsoRenderer: step must be in (0, 1], got " + std::to_string(step_index));
  step_ = step_index;
}

void VolumeIsoRenderer::set_filter_error(double fraction) {
  if (!(std::isfinite(fraction) && fraction >= 0x1p-24))
    throw std::invalid_argument("VolumeIsoRenderer: filter error must be finite and ≥ 2^-24, got " +
                                std::to_string(fraction));
  filter_error_ = fraction;
}

const ShaderProgram& VolumeIsoRenderer::program(bool hits) {
  ShaderDefines defines{{"ORDER", std::to_string(order_)}};
  if (hits) defines.push_back({"OUTPUT_HITS", ""});
  return programs_->get({"volume_iso.vert.glsl", "volume_iso.frag.glsl"}, defines);
}

void VolumeIsoRenderer::set_uniforms(const ShaderProgram& p, const glm::dmat4& view, const glm::dmat4& projection,
                                     const glm::ivec4& viewport, double iso) const {
  set_ivec3(p, "u_dims", dims_);
  set_ivec3(p, "u_brick_dims", brick_dims_);
  p.set("u_brick", brick_);
  p.set("u_iso", float(iso));
  p.set("u_step", float(step_));
  p.set("u_filter_error", float(filter_error_));
  p.set("u_viewport", glm::vec4(viewport));
  p.set("u_inv_proj", to_float(glm::inverse(projection)));
  p.set("u_view_to_index", to_float(world_to_index_ * glm::inverse(view)));
  p.set("u_index_to_clip", to_float(projection * view * index_to_world_));
  p.set("u_index_to_world", to_float(index_to_world_));
  p.set("u_gradient_to_world", glm::mat3(gradient_to_world_));
  p.set("u_box_max", glm::vec3(dims_[0] - 1, dims_[1] - 1, dims_[2] - 1));
}

void VolumeIsoRenderer::draw_box(const glm::dmat4& view, const glm::dmat4& projection) const {
  // The box's triangles are CCW from outside in index space. A projective map keeps or flips orientation by the sign
  // of its determinant; the standard GL projections have det < 0 and show outward CCW faces CCW on screen.
  const double det = glm::determinant(projection * view * index_to_world_);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glFrontFace(det < 0.0 ? GL_CCW : GL_CW);
  glCullFace(GL_FRONT);  // back faces: fragments even when the eye is inside the box
  glActiveTexture(GL_TEXTURE0 + kControlsUnit);
  glBindTexture(GL_TEXTURE_3D, controls_.id());
  glActiveTexture(GL_TEXTURE0 + kBricksUnit);
  glBindTexture(GL_TEXTURE_3D, bricks_.id());
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 36);
}

void VolumeIsoRenderer::draw(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport,
                             double iso, const IsoStyle& style) {
  if (!has_volume()) throw std::logic_error("VolumeIsoRenderer::draw: no volume (call set_volume)");
  const ShaderProgram& p = program(false);
  DrawStateGuard guard;
  p.use();
  set_uniforms(p, view, projection, viewport, iso);
  p.set("u_albedo", style.color);
  p.set("u_phong", glm::vec4(style.ambient, style.diffuse, style.specular, style.shininess));
  draw_box(view, projection);
  check_gl_error("VolumeIsoRenderer::draw");
}

// The framebuffer bindings, viewport, depth function and depth mask of the caller, restored on scope exit.
class TargetStateGuard {
 public:
  TargetStateGuard() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  }
  ~TargetStateGuard() {
    glDepthFunc(GLenum(depth_func_));
    glDepthMask(depth_mask_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  }
  TargetStateGuard(const TargetStateGuard&) = delete;
  TargetStateGuard& operator=(const TargetStateGuard&) = delete;

 private:
  GLint draw_ = 0, read_ = 0, viewport_[4] = {0, 0, 0, 0}, depth_func_ = GL_LESS;
  GLboolean depth_mask_ = GL_TRUE;
};

void VolumeIsoRenderer::bind_readback_target(int width, int height, const char* what) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument(std::string(what) + ": size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (!hits_fbo_ || hits_width_ != width || hits_height_ != height) {
    hits_position_ = make_texture_2d(GL_RGBA32F, width, height);
    hits_normal_ = make_texture_2d(GL_RGBA32F, width, height);
    hits_depth_ = make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    hits_fbo_ = Framebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, hits_fbo_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, hits_position_.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, hits_normal_.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, hits_depth_.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      hits_fbo_.reset();
      throw GlError(std::string(what) + ": framebuffer incomplete (status " + std::to_string(status) + ")");
    }
    hits_width_ = width, hits_height_ = height;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, hits_fbo_.id());
  glViewport(0, 0, width, height);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one = 1.0f;
  glDepthMask(GL_TRUE);
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, zero);
  glClearBufferfv(GL_DEPTH, 0, &one);
  glDepthFunc(GL_LESS);
}

std::vector<glm::vec4> VolumeIsoRenderer::read_attachment(int index) const {
  std::vector<glm::vec4> out(std::size_t(hits_width_) * std::size_t(hits_height_));
  GLint prev_pack = 4;
  glGetIntegerv(GL_PACK_ALIGNMENT, &prev_pack);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + index));
  glReadPixels(0, 0, hits_width_, hits_height_, GL_RGBA, GL_FLOAT, out.data());
  glPixelStorei(GL_PACK_ALIGNMENT, prev_pack);
  return out;
}

IsoHitReadback VolumeIsoRenderer::read_hits(const glm::dmat4& view, const glm::dmat4& projection, int width, int height,
                                            double iso) {
  if (!has_volume()) throw std::logic_error("VolumeIsoRenderer::read_hits: no volume (call set_volume)");
  const ShaderProgram& p = program(true);
  IsoHitReadback out;
  std::vector<glm::vec4> position, normal;
  {
    TargetStateGuard target;
    bind_readback_target(width, height, "VolumeIsoRenderer::read_hits");
    {
      DrawStateGuard guard;
      p.use();
      set_uniforms(p, view, projection, glm::ivec4(0, 0, width, height), iso);
      draw_box(view, projection);
    }
    position = read_attachment(0);
    normal = read_attachment(1);
    out.depth.resize(position.size());
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, out.depth.data());
  }
  check_gl_error("VolumeIsoRenderer::read_hits");
  const std::size_t count = position.size();
  out.width = width, out.height = height;
  out.hit.resize(count);
  out.world_point.resize(count);
  out.world_normal.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    out.hit[i] = position[i].w > 0.5f ? 1 : 0;
    out.world_point[i] = glm::vec3(position[i]);
    out.world_normal[i] = glm::vec3(normal[i]);
  }
  return out;
}

void VolumeIsoRenderer::draw_dvr(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport,
                                 const core::TransferFunction& transfer, double step_index, bool exact) {
  if (!has_volume()) throw std::logic_error("VolumeIsoRenderer::draw_dvr: no volume (call set_volume)");
  if (const std::string why = core::transfer_function_error(transfer); !why.empty())
    throw std::invalid_argument("VolumeIsoRenderer::draw_dvr: transfer function: " + why);
  if (!(std::isfinite(step_index) && step_index > 0.0 && step_index <= kMaxDvrStep))
    throw std::invalid_argument("VolumeIsoRenderer::draw_dvr: step must be in (0, " + std::to_string(kMaxDvrStep) +
                                "] index units, got " + std::to_string(step_index));
  ShaderDefines defines{{"ORDER", std::to_string(order_)}};
  if (exact) defines.push_back({"EXACT", ""});
  const ShaderProgram& p = programs_->get({"volume_iso.vert.glsl", "volume_dvr.frag.glsl"}, defines);
  DrawStateGuard guard;
  p.use();
  set_ivec3(p, "u_dims", dims_);
  set_ivec3(p, "u_brick_dims", brick_dims_);
  p.set("u_brick", brick_);
  p.set("u_step", float(step_index));
  p.set("u_opaque", float(core::kDvrOpaque));
  p.set("u_viewport", glm::vec4(viewport));
  p.set("u_inv_proj", to_float(glm::inverse(projection)));
  p.set("u_view_to_index", to_float(world_to_index_ * glm::inverse(view)));
  p.set("u_index_to_clip", to_float(projection * view * index_to_world_));
  p.set("u_box_max", glm::vec3(dims_[0] - 1, dims_[1] - 1, dims_[2] - 1));
  const int n = int(transfer.points.size());
  std::vector<float> values(n);
  std::vector<glm::vec4> rgba(n);
  for (int i = 0; i < n; ++i) values[i] = float(transfer.points[i].value), rgba[i] = glm::vec4(transfer.points[i].rgba);
  p.set("u_tf_count", n);
  glUniform1fv(p.uniform("u_tf_value"), n, values.data());
  glUniform4fv(p.uniform("u_tf_rgba"), n, &rgba[0].x);
  draw_box(view, projection);
  check_gl_error("VolumeIsoRenderer::draw_dvr");
}

std::vector<glm::vec4> VolumeIsoRenderer::read_dvr(const glm::dmat4& view, const glm::dmat4& projection, int width,
                                                   int height, const core::TransferFunction& transfer,
                                                   double step_index, bool exact) {
  std::vector<glm::vec4> out;
  {
    TargetStateGuard target;
    bind_readback_target(width, height, "VolumeIsoRenderer::read_dvr");
    GLboolean blend = glIsEnabled(GL_BLEND);
    glDisable(GL_BLEND);  // the cleared target: the fragment is the result
    draw_dvr(view, projection, glm::ivec4(0, 0, width, height), transfer, step_index, exact);
    if (blend) glEnable(GL_BLEND);
    out = read_attachment(0);
  }
  check_gl_error("VolumeIsoRenderer::read_dvr");
  return out;
}

}  // namespace trispline::gpu
