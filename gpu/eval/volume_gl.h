// trispline::gpu::VolumeIsoRenderer — the iso-surface D = c of a core::VolumeSpline ray cast in GLSL, exactly on
// the spline (seed §7.3; no mesh): the volume's grid box is rasterised (back faces, so the eye may be inside) and
// shaders/volume_iso.frag.glsl marches each pixel's ray as core::iso_ray_hit does (core/volume/iso_raycast.h: same
// rays and sample positions, the same first sign change, Illinois refinement), in float; shaded by the analytic
// gradient (Blinn–Phong, a headlight). It writes gl_FragDepth, so meshes and lines drawn with the depth test before or
// after it combine correctly.
//
// Speed without approximation: samples in bricks whose control-point range excludes c are never evaluated (a 3D DDA
// over the bricks), samples a brick's slope bound keeps on one side of c are skipped, the others are evaluated fast
// from 2³ GL_LINEAR fetches (Sigg & Hadwiger 2005) and only those whose fast value lies within its error bound of c,
// or changes sign, are evaluated exactly (ORDER³ texelFetch); the refinement and the normal use the (ORDER + 1)³
// control points around the bracket, fetched once. So every sign the march uses is the exact evaluation's and the
// image is the one of an exact march at every sample. The Cranium CT (256 × 256 × 108, tri-cubic) at 960 × 720 on
// llvmpipe costs about 1 CPU-second per frame (0.5–1.5 s wall on 2 shared cores).
//
//   IsoStyle                        colour and Phong terms of draw()
//   VolumeIsoRenderer::set_volume   uploads control points (3D R32F) and brick bounds (3D RGBA32F) once
//   VolumeIsoRenderer::draw         shaded iso-surface into the bound framebuffer
//   VolumeIsoRenderer::read_hits    world hit points, normals and depths per pixel (tests, picking)
//   VolumeIsoRenderer::draw_dvr     direct volume rendering through a transfer function (seed §7.4, Fig. 7.7)
//
// Tests hold the hits to the CPU reference on llvmpipe: the same hit/miss per pixel but for a silhouette band, world
// points within 1e-3 × the volume's size (tests/gpu/test_volume_gl.cpp); brick size and the fast path change no bit.
// Programs (one per order and output) are compiled at first use. All calls need the creating context (or one sharing
// with it) current.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/volume/volume_dvr.h"
#include "core/volume/volume_spline.h"
#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/gl_resource.h"
#include "gpu/gl/shader_program.h"

namespace trispline::gpu {

// Shading of draw(): albedo · (ambient + diffuse · max(n·v, 0)) + specular · max(n·v, 0)^shininess, light at the eye,
// both sides of the surface lit; written sRGB-encoded (the framebuffer is plain RGBA8, as the mesh shader's).
struct IsoStyle {
  glm::vec3 color{0.90f, 0.84f, 0.74f};  // albedo, linear RGB in [0, 1]
  float ambient = 0.15f;
  float diffuse = 0.85f;
  float specular = 0.25f;
  float shininess = 40.0f;
};

// Per-pixel result of read_hits, bottom row first (GL window rows): pixel (x, y) at x + width·y.
struct IsoHitReadback {
  int width = 0, height = 0;
  std::vector<unsigned char> hit;       // width·height, 1 = hit
  std::vector<glm::vec3> world_point;   // millimetres (0 for misses)
  std::vector<glm::vec3> world_normal;  // unit −∇D / |∇D| as core::IsoHit::world_normal (0 for misses)
  std::vector<float> depth;             // window depth in [0, 1] (what gl_FragDepth wrote), 1 for misses
  std::size_t hit_count() const;
};

class VolumeIsoRenderer {
 public:
  // `programs`: where compiled programs are kept (may be shared with other GL classes); null = a private cache.
  explicit VolumeIsoRenderer(std::shared_ptr<FfdProgramCache> programs = nullptr);
  ~VolumeIsoRenderer();
  VolumeIsoRenderer(const VolumeIsoRenderer&) = delete;
  VolumeIsoRenderer& operator=(const VolumeIsoRenderer&) = delete;

  // Uploads the spline's control points (nx × ny × nz R32F texels, GL_LINEAR) and its VolumeRangeGrid of
  // `brick`³-voxel bricks (RGBA32F: min, max, slope, 0) for empty-space skipping, replacing any previous volume; keeps
  // the order and the index ↔ world maps. Throws std::invalid_argument (a dimension above GL_MAX_3D_TEXTURE_SIZE,
  // brick < 1), GlError (e.g. out of memory).
  void set_volume(const core::VolumeSpline& spline, int brick = kDefaultBrick);
  bool has_volume() const { return dims_[0] > 0; }
  int uploads() const { return uploads_; }  // set_volume calls so far
  static constexpr int kDefaultBrick = 4;   // index units per brick axis

  // March step in index units (default 0.25, as core::iso_ray_hit). Throws std::invalid_argument unless in (0, 1]
  // (the refinement holds the control points of two knot spans per axis).
  void set_step(double step_index);
  double step() const { return step_; }

  // Bound of the GL_LINEAR filter's weight error per axis, as a fraction of a texel (default 2^-8: GPUs filter with
  // 8-bit weight fractions; llvmpipe in float). A fast value is trusted only farther than 3 × this × the brick's
  // control range from the iso-level, so a larger bound costs exact evaluations, never correctness; a huge one (tests)
  // evaluates every sample of the bricks holding the iso-level exactly. Throws std::invalid_argument unless finite and
  // ≥ 2^-24.
  void set_filter_error(double fraction);
  double filter_error() const { return filter_error_; }

  // Draws the iso-surface D = iso into the bound draw framebuffer, shaded with `style`: view / projection as
  // core::Camera's (OpenGL clip space, depth −1…1), `viewport` (x, y, width, height; pixels) the one set with
  // glViewport. Enables the depth test (the caller's depth function and mask; gl_FragDepth is the hit's depth) and
  // culls front faces for the draw; culling, front face, depth-test state and the vertex array and 3D textures of units
  // 0 and 1 are restored after, the volume's program stays in use. Throws
  // std::logic_error without a volume, ShaderError, GlError.
  void draw(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport, double iso,
            const IsoStyle& style = {});

  // Renders hits into a private width × height framebuffer (two RGBA32F colour attachments and a 32-bit float
  // depth buffer; viewport (0, 0, width, height)) and reads them back. Restores the framebuffer binding and
  // viewport. Throws as draw, std::invalid_argument for a non-positive size.
  IsoHitReadback read_hits(const glm::dmat4& view, const glm::dmat4& projection, int width, int height, double iso);

  // Direct volume rendering (shaders/volume_dvr.frag.glsl; the march of core::dvr_ray, core/volume/volume_dvr.h):
  // premultiplied RGBA with the colour sRGB-encoded, into the bound draw framebuffer, for blending with (ONE,
  // ONE_MINUS_SRC_ALPHA) (the caller's blend state); gl_FragDepth is the depth of the first sample that added
  // anything. `transfer`: as core::transfer_function_error accepts (values in the volume's units, opacity per index
  // unit); step_index: segment length in index units, (0, kMaxDvrStep]; exact: D from ORDER³ texel fetches per sample
  // instead of 2³ filtered ones (tests; about 8× slower). State as draw. Throws std::invalid_argument (transfer,
  // step), and as draw.
  void draw_dvr(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport,
                const core::TransferFunction& transfer, double step_index = 0.5, bool exact = false);
  static constexpr double kMaxDvrStep = 4.0;
  // draw_dvr into a private width × height RGBA32F framebuffer cleared to 0 (blending off), read back: width·height
  // premultiplied RGBA, bottom row first. Restores the framebuffer binding and viewport. Throws as draw_dvr,
  // std::invalid_argument for a non-positive size.
  std::vector<glm::vec4> read_dvr(const glm::dmat4& view, const glm::dmat4& projection, int width, int height,
                                  const core::TransferFunction& transfer, double step_index = 0.5, bool exact = false);

 private:
  const ShaderProgram& program(bool hits);
  void set_uniforms(const ShaderProgram& p, const glm::dmat4& view, const glm::dmat4& projection,
                    const glm::ivec4& viewport, double iso) const;
  void draw_box(const glm::dmat4& view, const glm::dmat4& projection) const;
  // Binds the read-back framebuffer (created or resized to width × height), sets the viewport, clears it.
  void bind_readback_target(int width, int height, const char* what);
  std::vector<glm::vec4> read_attachment(int index) const;  // colour attachment `index` of it, RGBA float

  std::shared_ptr<FfdProgramCache> programs_;
  Texture controls_, bricks_;
  VertexArray empty_vao_;
  std::array<int, 3> dims_{0, 0, 0};
  std::array<int, 3> brick_dims_{0, 0, 0};
  int brick_ = kDefaultBrick;
  int order_ = 4;
  glm::dmat4 index_to_world_{1.0}, world_to_index_{1.0};
  glm::dmat3 gradient_to_world_{1.0};
  double step_ = 0.25;
  double filter_error_ = 1.0 / 256.0;
  int uploads_ = 0;
  // read_hits' framebuffer, kept while the size does not change.
  Framebuffer hits_fbo_;
  Texture hits_position_, hits_normal_, hits_depth_;
  int hits_width_ = 0, hits_height_ = 0;
};

}  // namespace trispline::gpu
