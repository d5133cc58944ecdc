// The renderer's volume passes: iso-surfaces (ray cast, depth-combined with meshes) and silhouette strokes. See
// renderer_volume.h.
#include "gpu/render/renderer_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <unordered_set>

#include "gpu/render/renderer_impl.h"

namespace trispline::gpu {
namespace detail {

ShownVolume shown_volume(const core::VolumeObject& v, const ViewOptions& options) {
  ShownVolume s{v.iso, v.silhouette.enabled ? v.silhouettes : nullptr, {}};
  if (v.silhouette.enabled)
    for (const core::VolumeIsoLevel& l : v.more_levels) s.more_silhouettes.push_back(l.silhouettes);
  if (const VolumeInPlace* in = options.overlays.volume_for(v.name)) {
    if (in->iso) s.iso = *in->iso;
    if (in->silhouettes && v.silhouette.enabled) s.silhouettes = in->silhouettes;
    if (v.silhouette.enabled && in->more_silhouettes.size() == v.more_levels.size())
      s.more_silhouettes = in->more_silhouettes;
  }
  return s;
}

SilhouetteStrokeStyle level_stroke_style(const core::VolumeObject& v, const core::VolumeIsoLevel& level,
                                         const ViewStyle& style) {
  SilhouetteStrokeStyle s = silhouette_stroke_style(v, style);
  s.stroke = level.style;
  s.plain_color = glm::vec4(level.color, 1.0f);
  return s;
}

SilhouetteStrokeStyle silhouette_stroke_style(const core::VolumeObject& v, const ViewStyle& style) {
  SilhouetteStrokeStyle s;
  s.stroke = v.silhouette.style;
  s.hidden = v.silhouette.hidden;
  s.width_px = std::max(style.silhouette_width_px, 0.1f);
  s.max_width_px = std::max(style.silhouette_max_width_px, s.width_px);
  s.hidden_color = style.silhouette_hidden_color;
  s.dash_px = style.silhouette_dash_px;
  s.gap_px = style.silhouette_gap_px;
  const double voxel = std::cbrt(std::abs(glm::determinant(glm::dmat3(v.spline->index_to_world()))));
  const int subdivision = std::max(v.silhouette.params.subdivision, 1);
  s.glyph_mm = std::isfinite(voxel) && voxel > 0.0 ? voxel / subdivision : 1.0;
  const double diagonal = v.world_bounds().diagonal();
  s.depth_pull_mm = std::isfinite(diagonal) ? style.silhouette_depth_pull * diagonal : 0.0;
  return s;
}

bool VolumeDisplay::any_surface(const core::Scene& scene) {
  return std::any_of(scene.volumes().begin(), scene.volumes().end(),
                     [](const core::VolumeObject& v) { return v.visible && v.show_surface && v.spline; });
}

VolumeIsoRenderer& VolumeDisplay::renderer_for(const core::VolumeObject& v, int* uploads) {
  Cached& c = cache_[v.spline.get()];
  if (c.spline != v.spline || !c.gl) {
    auto gl = std::make_unique<VolumeIsoRenderer>(programs_);
    gl->set_volume(*v.spline);
    c.gl = std::move(gl);
    c.spline = v.spline;
    if (uploads) ++*uploads;
  }
  return *c.gl;
}

void VolumeDisplay::release_unused(const core::Scene& scene) {
  std::unordered_set<const core::VolumeSpline*> live;
  for (const core::VolumeObject& v : scene.volumes())
    if (v.spline) live.insert(v.spline.get());
  if (std::erase_if(cache_, [&](const auto& kv) { return !live.count(kv.first); }) > 0) has_key_ = false;
  if (cache_.empty()) {
    full_ = Target{};
    preview_ = Target{};
  }
}

void VolumeDisplay::Target::ensure(glm::ivec2 want) {
  if (fbo && size == want) return;
  auto texture = [&](GLenum internal) {
    Texture t = Texture::create();
    glBindTexture(GL_TEXTURE_2D, t.id());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal, want.x, want.y);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
  };
  color = texture(GL_RGBA8);
  depth = texture(GL_DEPTH_COMPONENT32F);
  fbo = Framebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id(), 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fbo.reset();
    throw GlError("volume layer: framebuffer incomplete (status " + std::to_string(status) + ")");
  }
  size = want;
}

double VolumeDisplay::cast(Target& t, const std::vector<ShownSurface>& surfaces, const glm::dmat4& view,
                           const glm::dmat4& projection, int row0, int rows, int* uploads) {
  glFinish();  // the wall time below is this cast's alone
  const auto t0 = std::chrono::steady_clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.id());
  glViewport(0, 0, t.size.x, t.size.y);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, row0, t.size.x, rows);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one = 1.0f;
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_DEPTH, 0, &one);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const glm::ivec4 viewport(0, 0, t.size.x, t.size.y);
  for (const ShownSurface& s : surfaces) {
    if (s.dvr) {  // premultiplied, over what the layer holds
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      renderer_for(*s.volume, uploads).draw_dvr(view, projection, viewport, s.volume->transfer, s.volume->dvr_step);
      glDisable(GL_BLEND);
      continue;
    }
    IsoStyle style;
    style.color = s.color;
    renderer_for(*s.volume, uploads).draw(view, projection, viewport, s.iso, style);
  }
  glDisable(GL_SCISSOR_TEST);
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

LayerUpdate VolumeDisplay::update_layer(const std::vector<ShownSurface>& surfaces, const glm::dmat4& view,
                                        const glm::dmat4& projection, glm::ivec2 vp, double budget_ms, int* uploads) {
  LayerUpdate u;
  if (vp.x <= 0 || vp.y <= 0) return u;
  Key key{view, projection, vp, {}};
  for (const ShownSurface& s : surfaces) {
    key.surfaces.emplace_back(s.volume->spline.get(), s.dvr ? 0.0 : s.iso, s.color);
    key.dvr.emplace_back(s.dvr ? s.volume->transfer : core::TransferFunction{}, s.dvr ? s.volume->dvr_step : 0.0);
  }
  // Per-pixel cost of the last cast: up at once, down by half at most (an empty band costs nearly nothing and must
  // not make the next one huge).
  auto measure = [&](double ms, std::size_t pixels) {
    if (pixels == 0) return;
    const double m = ms / double(pixels);
    ms_per_pixel_ = ms_per_pixel_ < 0.0 || m > ms_per_pixel_ ? m : std::max(m, 0.5 * ms_per_pixel_);
  };
  const std::size_t frame_pixels = std::size_t(vp.x) * std::size_t(vp.y);
  if (!has_key_ || !(key == key_)) {
    key_ = std::move(key);
    has_key_ = true;
    full_.ensure(vp);
    const double estimate = ms_per_pixel_ >= 0.0 ? ms_per_pixel_ * double(frame_pixels) : -1.0;
    if (budget_ms <= 0.0 || (estimate >= 0.0 && estimate <= budget_ms)) {
      measure(cast(full_, surfaces, view, projection, 0, vp.y, uploads), frame_pixels);
      refined_rows_ = vp.y;
      u.cast_pixels = frame_pixels;
    } else {
      preview_scale_ = estimate < 0.0 ? 0.25f : float(std::clamp(std::sqrt(budget_ms / estimate), 0.125, 0.5));
      const glm::ivec2 size = glm::max(glm::ivec2(glm::round(glm::vec2(vp) * preview_scale_)), glm::ivec2(1));
      preview_.ensure(size);
      const std::size_t pixels = std::size_t(size.x) * std::size_t(size.y);
      measure(cast(preview_, surfaces, view, projection, 0, size.y, uploads), pixels);
      refined_rows_ = 0;
      u.cast_pixels = pixels;
    }
  } else if (refined_rows_ < vp.y) {
    const double per_row = std::max(ms_per_pixel_ * vp.x, 1e-9);
    const int rows = std::clamp(int(budget_ms / per_row), std::min(16, vp.y - refined_rows_), vp.y - refined_rows_);
    measure(cast(full_, surfaces, view, projection, vp.y - refined_rows_ - rows, rows, uploads),
            std::size_t(vp.x) * std::size_t(rows));
    refined_rows_ += rows;
    u.cast_pixels = std::size_t(vp.x) * std::size_t(rows);
  }
  u.refining = refined_rows_ < vp.y;
  u.scale = u.refining ? preview_scale_ : 1.0f;
  return u;
}

void VolumeDisplay::composite(const ShaderProgram& p, glm::ivec2 vp, GLuint empty_vao) const {
  const Target& preview = preview_.fbo ? preview_ : full_;
  p.set("u_refined_from", float(vp.y - refined_rows_));
  p.set("u_viewport", glm::vec2(vp));
  const GLuint textures[4] = {full_.color.id(), full_.depth.id(), preview.color.id(), preview.depth.id()};
  for (GLuint unit = 0; unit < 4; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, textures[unit]);
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  for (GLuint unit = 4; unit-- > 0;) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
}

}  // namespace detail

using detail::Frame;

void Renderer::Impl::pass_volumes(const Frame& f, std::optional<GpuTimer::Scope>& draw_scope, GpuTimer& resume) {
  // Timed on their own (the draw timer pauses around them); stencil untouched (the outline mask is the objects').
  if (!detail::VolumeDisplay::any_surface(f.scene)) return;
  draw_scope.reset();
  {
    GpuTimer::Scope scope(volume_timer);
    GLint draw_fbo = 0, read_fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    // The selection tint: an eighth of the selection colour (display values → linear, as the albedo).
    const glm::vec3 tint = glm::pow(glm::clamp(f.style().selection_color, 0.0f, 1.0f), glm::vec3(2.2f));
    std::vector<detail::ShownSurface> surfaces;
    for (const core::VolumeObject& v : f.scene.volumes()) {
      if (!v.visible || !v.show_surface || !v.spline) continue;
      const bool selected = !f.options.selected.empty() && v.name == f.options.selected;
      const bool dvr = v.render_mode == core::VolumeObject::RenderMode::dvr && !v.transfer.points.empty();
      surfaces.push_back(
          {&v, detail::shown_volume(v, f.options).iso, selected ? glm::mix(v.color, tint, 0.125f) : v.color, dvr});
    }
    const detail::LayerUpdate u = volumes.update_layer(surfaces, f.camera.view_matrix(), f.camera.projection_matrix(),
                                                       f.vp, f.options.volume_budget_ms, &stats.volume_uploads);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fbo));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fbo));
    glViewport(0, 0, f.vp.x, f.vp.y);
    glDisable(GL_STENCIL_TEST);
    // The layer is premultiplied (iso-surfaces opaque, direct volume rendering translucent): over the frame.
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    volume_layer.use();
    volumes.composite(volume_layer, f.vp, empty_vao.id());
    glDisable(GL_BLEND);
    stats.volumes_drawn = int(surfaces.size());
    stats.volume_cast_pixels = u.cast_pixels;
    stats.volume_refining = u.refining;
    stats.volume_scale = u.scale;
  }
  stats.volume_ms = volume_timer.last_ms();
  draw_scope.emplace(resume);
}

void Renderer::Impl::pass_volume_silhouettes(const Frame& f) {
  if (f.scene.volumes().empty()) return;
  const glm::dmat4 view_proj = f.camera.projection_matrix() * f.camera.view_matrix();
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  for (const core::VolumeObject& v : f.scene.volumes()) {
    if (!v.visible || !v.spline) continue;
    const bool selected = !f.options.selected.empty() && v.name == f.options.selected;
    if (selected) {
      // The grid box, x-ray: where the volume is, even at a level that shows nothing.
      const auto& d = v.spline->dims();
      glm::vec3 c[8];
      for (int k = 0; k < 8; ++k)
        c[k] = glm::vec3(v.spline->index_to_world() *
                         glm::dvec4((k & 1) ? d[0] - 1 : 0, (k & 2) ? d[1] - 1 : 0, (k & 4) ? d[2] - 1 : 0, 1.0));
      std::vector<OverlayVertex> edges;
      const glm::vec4 color = detail::rgba(f.style().selection_color, 0.8f);
      for (int k = 0; k < 8; ++k)
        for (int bit : {1, 2, 4})
          if (!(k & bit)) edges.insert(edges.end(), {{c[k], color}, {c[k | bit], color}});
      draw_xray(edges, {}, f.view_proj, 1.0f);
    }
    const detail::ShownVolume shown = detail::shown_volume(v, f.options);
    // Every level's strokes: the first level's in the volume's style, each further level's in its own.
    std::vector<std::pair<const core::SilhouetteResult*, SilhouetteStrokeStyle>> levels;
    if (shown.silhouettes) levels.emplace_back(shown.silhouettes.get(), detail::silhouette_stroke_style(v, f.style()));
    for (std::size_t i = 0; i < shown.more_silhouettes.size() && i < v.more_levels.size(); ++i)
      if (shown.more_silhouettes[i])
        levels.emplace_back(shown.more_silhouettes[i].get(),
                            detail::level_stroke_style(v, v.more_levels[i], f.style()));
    for (const auto& [result, stroke_style] : levels) {
      const SilhouetteStrokes strokes =
          build_silhouette_strokes(result->polylines, view_proj, f.vp, f.camera.eye, stroke_style);
      stats.silhouette_points += strokes.points;
      screen_depth.use();
      screen_depth.set("u_viewport", glm::vec2(f.vp));
      glDepthMask(GL_FALSE);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LEQUAL);
      draw_overlay(strokes.depth_tested, GL_TRIANGLES, screen_depth, 1.0f);
      glDisable(GL_DEPTH_TEST);
      draw_overlay(strokes.on_top, GL_TRIANGLES, screen_depth, 1.0f);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
    }
  }
}

}  // namespace trispline::gpu
