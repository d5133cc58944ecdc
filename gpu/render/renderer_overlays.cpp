// Renderer passes drawn over the shaded scene: contact surfaces, control lattices and contact samples, DFFD
// discontinuity planes and fold-overs, and ViewOptions::overlays (spheres, points, lattices, curves, strokes).
#include <algorithm>
#include <cmath>

#include "gpu/render/renderer_impl.h"

namespace trispline::gpu {

using detail::Frame;

namespace {

// An overlay over the surface: depth-tested (ties drawn), no depth writes, both faces.
void overlay_depth_state() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
}

// `program` (built with DEPTH_PULL) in use for the frame's view, pulled towards the eye by `depth_pull` (a fraction
// of the eye distance) so that it is not lost in z-fighting with the surface under it.
void use_pulled(ShaderProgram& program, const Frame& f, float depth_pull) {
  program.use();
  program.set("u_view_proj", f.view_proj);
  program.set("u_eye", f.eye);
  program.set("u_depth_pull", depth_pull);
}

}  // namespace

void detail::StreamBuffer::init(bool screen_space) {
  vao = VertexArray::create();
  vbo = Buffer::create();
  glBindVertexArray(vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
  const GLsizei stride = sizeof(OverlayVertex);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, screen_space ? 2 : 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(OverlayVertex, color)));
  glBindVertexArray(0);
}

void detail::StreamBuffer::upload(const std::vector<OverlayVertex>& v) {
  if (!vao) init(false);
  glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
  const GLsizeiptr bytes = GLsizeiptr(v.size() * sizeof(OverlayVertex));
  if (bytes > capacity) {
    capacity = std::max<GLsizeiptr>(bytes, 2 * capacity);
    glBufferData(GL_ARRAY_BUFFER, capacity, nullptr, GL_STREAM_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, v.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

detail::CachedContactSurface& Renderer::Impl::contact_surface(const std::shared_ptr<const core::FfdBinding>& ffd,
                                                              const ViewStyle& o) {
  const int cells_u = std::max(o.contact_cells_u, 1), cells_v = std::max(o.contact_cells_v, 1);
  detail::CachedContactSurface& c = contact_cache[ffd.get()];
  if (c.ffd != ffd || c.cells_u != cells_u || c.cells_v != cells_v || c.iso_every != o.contact_iso_every ||
      c.iso_color != o.contact_iso_color) {
    const ContactSurfaceTessellation t = tessellate_contact_surface(ffd->lattice, cells_u, cells_v);
    std::vector<OverlayVertex> iso;
    append_contact_iso_lines(t, o.contact_iso_every, o.contact_iso_every, o.contact_iso_color, iso);
    c.ffd = ffd;
    c.cells_u = cells_u;
    c.cells_v = cells_v;
    c.iso_every = o.contact_iso_every;
    c.iso_color = o.contact_iso_color;
    c.surface.upload(t.mesh);
    c.iso.upload(iso);
    c.iso_vertices = GLsizei(iso.size());
    ++stats.contact_uploads;
  }
  return c;
}

// Depth test on, no depth writes, both faces; sheets and iso-lines are pulled a little towards the eye so they
// are not lost in z-fighting with the surface they were fitted to.
void Renderer::Impl::draw_contact_surfaces(const Frame& f) {
  constexpr float kDepthPull = 0.003f;  // fraction of the eye distance
  std::vector<detail::CachedContactSurface*> todo;
  for (const core::SceneObject& obj : f.scene.objects())
    if (obj.visible && obj.ffd) todo.push_back(&contact_surface(obj.ffd, f.style()));
  if (todo.empty()) return;
  overlay_depth_state();
  use_pulled(sheet, f, kDepthPull);
  sheet.set("u_tint", f.style().contact_surface_color);
  for (detail::CachedContactSurface* c : todo) {
    c->surface.draw_triangles();
    ++stats.contact_surfaces_drawn;
  }
  use_pulled(pulled_lines, f, kDepthPull);
  pulled_lines.set("u_point_px", 1.0f);
  pulled_lines.set("u_alpha", 1.0f);
  for (detail::CachedContactSurface* c : todo) {
    if (c->iso_vertices == 0) continue;
    glBindVertexArray(c->iso.vao.id());
    glDrawArrays(GL_LINES, 0, c->iso_vertices);
  }
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

void Renderer::Impl::draw_overlay(const std::vector<OverlayVertex>& v, GLenum mode, const ShaderProgram& prog,
                                  float alpha) {
  if (v.empty()) return;
  world_stream.upload(v);
  prog.set("u_alpha", alpha);
  glBindVertexArray(world_stream.vao.id());
  glDrawArrays(mode, 0, GLsizei(v.size()));
}

void Renderer::Impl::draw_screen_polyline(const std::vector<glm::dvec2>& px, float width_px, const glm::vec4& color,
                                          const glm::ivec2& vp) {
  if (px.empty()) return;
  const std::vector<glm::vec2> tris = thick_polyline(px, width_px);
  std::vector<OverlayVertex> v;
  v.reserve(tris.size());
  for (const glm::vec2& p : tris) v.push_back({glm::vec3(p, 0.0f), color});
  glDisable(GL_DEPTH_TEST);
  screen.use();
  screen.set("u_viewport", glm::vec2(vp));
  screen.set("u_alpha", 1.0f);
  screen_stream.upload(v);
  glBindVertexArray(screen_stream.vao.id());
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(v.size()));
  glEnable(GL_DEPTH_TEST);
}

void Renderer::Impl::draw_xray(const std::vector<OverlayVertex>& lines_v, const std::vector<OverlayVertex>& points_v,
                               const glm::mat4& view_proj, float point_px) {
  lines.use();
  lines.set("u_view_proj", view_proj);
  glDisable(GL_DEPTH_TEST);
  draw_overlay(lines_v, GL_LINES, lines, 0.22f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  draw_overlay(lines_v, GL_LINES, lines, 1.0f);
  points.use();
  points.set("u_view_proj", view_proj);
  points.set("u_point_px", point_px);
  glDisable(GL_DEPTH_TEST);
  draw_overlay(points_v, GL_POINTS, points, 0.3f);
  glEnable(GL_DEPTH_TEST);
  draw_overlay(points_v, GL_POINTS, points, 1.0f);
  glDepthFunc(GL_LESS);
}

void Renderer::Impl::pass_lattices_and_contacts(const Frame& f) {
  const ViewOptions& options = f.options;
  const ViewStyle& style = f.style();
  // 5. Contact surfaces (translucent, after every opaque mesh), lattices and contact samples on top.
  if (options.show_contact_surface) draw_contact_surfaces(f);
  if (!options.show_lattice && !options.show_contact_surface) return;
  std::vector<OverlayVertex> lines_v, points_v;
  for (const core::SceneObject& o : f.scene.objects()) {
    if (!o.visible || !options.show_lattice) continue;
    if (o.ffd) append_lattice(o.ffd->lattice, style.lattice_line_color, style.lattice_point_color, lines_v, points_v);
    if (o.dffd) append_lattice(o.dffd->lattice, style.lattice_line_color, style.lattice_point_color, lines_v, points_v);
  }
  draw_xray(lines_v, points_v, f.view_proj, style.lattice_point_px);
  lines_v.clear();
  points_v.clear();
  for (const core::SceneObject& o : f.scene.objects())
    if (options.show_contact_surface && o.visible && o.placement)
      append_contact_surface(*o.placement, style.contact_hit_color, style.contact_filled_color,
                             style.contact_grid_color, lines_v, points_v);
  draw_xray(lines_v, points_v, f.view_proj, style.contact_point_px);
}

void Renderer::Impl::pass_discontinuities(const Frame& f) {
  const ViewOptions& o = f.options;
  const ViewStyle& style = f.style();
  // 5b. DFFD objects' discontinuity planes (F⁻ larger, F⁺ on top, x-ray) and fold-over points (on top of
  // everything); which objects: see ViewOptions::show_discontinuities.
  std::vector<OverlayVertex> plane_lines, minus_points, plus_points, folds;
  for (const core::SceneObject& obj : f.scene.objects()) {
    if (!obj.visible || !obj.dffd) continue;
    const bool selected = !o.selected.empty() && obj.name == o.selected;
    if (o.show_discontinuities && (o.show_lattice || selected))
      append_discontinuity_planes(obj.dffd->lattice, obj.dffd->discontinuities, style.dffd_minus_color,
                                  style.dffd_plus_color, plane_lines, minus_points, plus_points);
    if (o.show_lattice || selected)
      for (const glm::dvec3& p : obj.dffd->fold_points) folds.push_back({glm::vec3(p), style.fold_point_color});
  }
  if (!plane_lines.empty() || !minus_points.empty()) {
    draw_xray(plane_lines, minus_points, f.view_proj, 1.7f * style.lattice_point_px);
    draw_xray({}, plus_points, f.view_proj, style.lattice_point_px);
  }
  if (!folds.empty()) {
    points.use();
    points.set("u_view_proj", f.view_proj);
    points.set("u_point_px", style.fold_point_px);
    glDisable(GL_DEPTH_TEST);
    draw_overlay(folds, GL_POINTS, points, 1.0f);
    glEnable(GL_DEPTH_TEST);
  }
}

void Renderer::Impl::pass_world_overlays(const Frame& f) {
  const Overlays& overlays = f.options.overlays;
  const ViewStyle& style = f.style();
  // 6a. Translucent spheres: blended, depth-tested, no depth writes, back faces culled.
  if (!overlays.spheres.empty()) {
    std::vector<OverlayVertex> tris;
    for (const SphereOverlay& s : overlays.spheres) append_sphere(s, f.eye, tris);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    lines.use();
    lines.set("u_view_proj", f.view_proj);
    draw_overlay(tris, GL_TRIANGLES, lines, 1.0f);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_TRUE);
  }
  // 6a'. Coloured triangles (heat maps) on the surfaces they were made for: depth-tested, pulled towards the eye,
  // blended, no depth writes; cached per corner array, dropped when no longer shown.
  for (auto& [key, c] : colored_cache) c.used = false;
  if (!overlays.colored_triangles.empty()) {
    constexpr float kDepthPull = 0.002f;  // fraction of the eye distance
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    overlay_depth_state();
    use_pulled(pulled_lines, f, kDepthPull);
    pulled_lines.set("u_point_px", 1.0f);
    pulled_lines.set("u_alpha", 1.0f);
    for (const ColoredTrianglesOverlay& t : overlays.colored_triangles) {
      if (!t.corners || !t.colors || t.colors->size() != t.corners->size() || t.corners->empty()) continue;
      detail::CachedColoredTriangles& c = colored_cache[t.corners.get()];
      if (c.corners != t.corners || c.colors != t.colors) {
        std::vector<OverlayVertex> v(t.corners->size());
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = {(*t.corners)[i], (*t.colors)[i]};
        c.buffer.upload(v);
        c.vertices = GLsizei(v.size() - v.size() % 3);
        c.corners = t.corners;
        c.colors = t.colors;
      }
      c.used = true;
      glBindVertexArray(c.buffer.vao.id());
      glDrawArrays(GL_TRIANGLES, 0, c.vertices);
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }
  std::erase_if(colored_cache, [](const auto& kv) { return !kv.second.used; });
  // 6a''. Coloured segments, x-ray.
  for (const ColoredLinesOverlay& l : overlays.colored_lines) {
    std::vector<OverlayVertex> v;
    v.reserve(l.ends.size());
    for (std::size_t i = 0; i + 1 < l.ends.size() && i / 2 < l.colors.size(); i += 2) {
      v.push_back({glm::vec3(l.ends[i]), l.colors[i / 2]});
      v.push_back({glm::vec3(l.ends[i + 1]), l.colors[i / 2]});
    }
    draw_xray(v, {}, f.view_proj, 1.0f);
  }
  // 6b. Point sets, x-ray.
  for (const PointsOverlay& set : overlays.points) {
    std::vector<OverlayVertex> v;
    v.reserve(set.points.size());
    for (const glm::dvec3& p : set.points) v.push_back({glm::vec3(p), set.color});
    draw_xray({}, v, f.view_proj, set.point_px);
  }
  // 6c. Lattices: the net, then the discontinuity planes it names.
  for (const LatticeOverlay& l : overlays.lattices) {
    if (!l.lattice) continue;
    std::vector<OverlayVertex> net_lines, net_points;
    append_lattice(*l.lattice, l.line_color, l.point_color, net_lines, net_points);
    draw_xray(net_lines, net_points, f.view_proj, l.point_px);
    if (!f.options.show_discontinuities || l.discontinuities.empty()) continue;
    std::vector<OverlayVertex> plane_lines, minus_points, plus_points;
    append_discontinuity_planes(*l.lattice, l.discontinuities, style.dffd_minus_color, style.dffd_plus_color,
                                plane_lines, minus_points, plus_points);
    draw_xray(plane_lines, minus_points, f.view_proj, 1.7f * style.lattice_point_px);
    draw_xray({}, plus_points, f.view_proj, style.lattice_point_px);
  }
}

void Renderer::Impl::pass_screen_overlays(const Frame& f) {
  const Overlays& overlays = f.options.overlays;
  // 7. Curves (projected; split where they pass behind the eye), then strokes: thick screen-space polylines on top
  // of everything.
  for (const CurveOverlay& curve : overlays.curves) {
    std::vector<glm::dvec2> run;
    for (std::size_t i = 0; i <= curve.points.size(); ++i) {
      const glm::dvec3 p = i < curve.points.size() ? f.camera.project(curve.points[i]) : glm::dvec3(0.0);
      if (i < curve.points.size() && p.z > 0.0 && std::isfinite(p.x) && std::isfinite(p.y)) {
        run.emplace_back(p.x, p.y);
        continue;
      }
      draw_screen_polyline(run, curve.width_px, curve.color, f.vp);
      run.clear();
    }
  }
  for (const ScreenStroke& s : overlays.strokes) draw_screen_polyline(s.px, s.width_px, s.color, f.vp);
}

}  // namespace trispline::gpu
