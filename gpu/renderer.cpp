#include "gpu/renderer.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "gpu/overlay_geometry.h"
#include "gpu/renderer_ddm.h"
#include "gpu/renderer_ffd.h"
#include "gpu/shader_program.h"
#include "gpu/timer.h"

namespace trispline::gpu {
namespace {

struct CachedMesh {
  std::shared_ptr<const core::TriMesh> mesh;  // held so the address cannot be reused by another mesh
  MeshBuffers buffers;
  std::uint64_t generation = 0;  // changes whenever the buffers' contents change (upload, FFD write)
  bool overwritten = false;      // the buffers hold an FFD evaluation rather than world_mesh
};

// A growable stream buffer for per-frame overlay geometry (small: lattices, contact grids, the stroke).
struct StreamBuffer {
  VertexArray vao;
  Buffer vbo;
  GLsizeiptr capacity = 0;
  void init(bool screen_space) {
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
  void upload(const std::vector<OverlayVertex>& v) {
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
};

// The contact surface S(u,v) = F(u,v,0) of one FfdBinding on the GPU: the tessellation (MeshBuffers layout, drawn
// translucent) and its iso-lines (OverlayVertex GL_LINES). Built once per binding and settings.
struct CachedContactSurface {
  std::shared_ptr<const core::FfdBinding> ffd;  // held so the address cannot be reused by another binding
  int cells_u = 0, cells_v = 0, iso_every = 0;
  glm::vec4 iso_color{0.0f};
  MeshBuffers surface;
  StreamBuffer iso;  // static after the build (uploaded once)
  GLsizei iso_vertices = 0;
};

glm::vec4 rgba(const glm::vec3& c, float a = 1.0f) { return {c, a}; }

// The mesh drawn for `o`: the incision preview mesh when the options name `o`, else its world_mesh.
const std::shared_ptr<const core::TriMesh>& shown_mesh(const core::SceneObject& o, const ViewOptions& opt) {
  const bool preview = opt.incision_preview_mesh && o.name == opt.incision_preview_object;
  return preview ? opt.incision_preview_mesh : o.world_mesh;
}

// Power of ten a tenth of the scene's size: minor grid cell, world units.
float grid_cell_for(const core::Scene& scene) {
  const core::Aabb b = scene.bounds();
  const double size = b.valid() ? std::max(b.diagonal(), 1e-6) : 2.0;
  return float(std::pow(10.0, std::floor(std::log10(size)) - 1.0));
}

// What every pass of Renderer::draw reads: the scene, the view and its matrices, the FFD plan per object.
struct Frame {
  const core::Scene& scene;
  const core::Camera& camera;
  const ViewOptions& options;
  glm::ivec2 vp;         // viewport, pixels
  glm::mat4 view_proj;   // world → clip
  glm::vec3 eye;         // world units
  glm::vec3 key;         // unit key-light direction
  std::vector<detail::FfdPlan> plans;  // per scene object
};

// The selected object (it writes stencil 1 for the outline), when it was drawn.
struct SelectedObject {
  const core::SceneObject* object = nullptr;
  std::size_t index = 0;
};

}  // namespace

struct Renderer::Impl {
  // The passes of Renderer::draw, in order; each leaves the GL state the next expects.
  void pass_clear(const Frame& f);       // known state (ImGui leaves its own), cleared to the background colour
  void pass_background(const Frame& f);  // 1. the background gradient
  SelectedObject pass_objects(const Frame& f);  // 2. shaded objects; the selected one writes stencil 1
  void pass_wireframe(const Frame& f);          // 2b. dark edges over the shaded surfaces
  void pass_grid(const Frame& f);               // 3. the ground grid
  void pass_selection_outline(const Frame& f, const SelectedObject& sel);  // 4. the selection outline
  void pass_lattices_and_contacts(const Frame& f);  // 5. contact surfaces, lattices, contact samples
  void pass_brush(const Frame& f);                  // 5b. the pressing brush and its path
  void pass_cut_overlays(const Frame& f);           // 5c. DFFD planes and fold-overs, the incision preview lattice
  void pass_screen_overlays(const Frame& f);        // 6. the incision curve and the sketched stroke, on top

  ShaderProgram background{{"background.vert.glsl", "background.frag.glsl"}};
  ShaderProgram mesh{{"mesh.vert.glsl", "mesh.frag.glsl"}};
  ShaderProgram flat{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"FLAT_COLOR", ""}}};
  ShaderProgram outline{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}}};
  ShaderProgram grid{{"grid.vert.glsl", "grid.frag.glsl"}};
  ShaderProgram lines{{"lines.vert.glsl", "lines.frag.glsl"}};
  ShaderProgram points{{"lines.vert.glsl", "lines.frag.glsl"}, {{"ROUND_POINTS", ""}}};
  ShaderProgram screen{{"lines.vert.glsl", "lines.frag.glsl"}, {{"SCREEN_SPACE", ""}}};
  ShaderProgram sheet{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"DEPTH_PULL", ""}, {"TRANSLUCENT", ""}}};
  ShaderProgram pulled_lines{{"lines.vert.glsl", "lines.frag.glsl"}, {{"DEPTH_PULL", ""}}};
  VertexArray empty_vao = VertexArray::create();  // attribute-less full-screen passes
  StreamBuffer world_stream, screen_stream;
  std::unordered_map<const core::TriMesh*, CachedMesh> cache;
  std::unordered_map<const core::FfdBinding*, CachedContactSurface> contact_cache;
  std::shared_ptr<FfdProgramCache> ffd_programs = std::make_shared<FfdProgramCache>();
  detail::FfdDisplay ffd{ffd_programs};
  detail::DdmDisplay ddm{ffd_programs};
  GpuTimer ddm_timer, draw_timer_b;  // the DDM pass; the drawing passes after it (timers cannot nest)
  std::uint64_t generation = 0;  // source of CachedMesh::generation values
  GpuTimer ffd_timer, draw_timer;
  RenderStats stats;
  std::shared_ptr<const core::TriMesh> preview;  // the incision preview mesh of the current draw (kept cached)

  Impl() {
    world_stream.init(false);
    screen_stream.init(true);
  }

  CachedMesh& cached(const std::shared_ptr<const core::TriMesh>& m) {
    auto [it, inserted] = cache.try_emplace(m.get());
    if (inserted) {
      it->second.mesh = m;
      it->second.buffers.upload(*m);
      it->second.generation = ++generation;
      ++stats.uploads;
    }
    return it->second;
  }
  MeshBuffers& buffers(const std::shared_ptr<const core::TriMesh>& m) { return cached(m).buffers; }

  // FFD pass: brings every visible deformed object's display up to date; plans[i] says how to draw object i.
  void prepare_ffd(const core::Scene& scene, const ViewOptions& o, std::vector<detail::FfdPlan>& plans) {
    const std::vector<core::SceneObject>& objects = scene.objects();
    plans.assign(objects.size(), {});
    bool any = false;
    for (const core::SceneObject& obj : objects) any = any || (obj.visible && obj.ffd && obj.world_mesh);
    if (!any) return;
    double cpu_ms = 0.0;
    {
      GpuTimer::Scope scope(ffd_timer);
      for (std::size_t i = 0; i < objects.size(); ++i) {
        const core::SceneObject& obj = objects[i];
        if (!obj.visible || !obj.ffd || !obj.world_mesh || obj.world_mesh->empty()) continue;
        if (shown_mesh(obj, o) != obj.world_mesh) continue;  // replaced by the incision preview: drawn as it is
        if (obj.ffd->params.size() != obj.world_mesh->positions.size()) continue;  // inconsistent: draw world_mesh
        CachedMesh& c = cached(obj.world_mesh);
        const bool live = o.live_lattice && obj.name == o.live_ffd_object &&
                          o.live_lattice->control_counts() == obj.ffd->lattice.control_counts();
        plans[i] = ffd.prepare(obj, {&c.buffers, &c.generation, &c.overwritten, c.mesh.get()}, o.ffd_backend, o.time_s,
                               generation, &stats.ffd_vertices, &cpu_ms, &stats.uploads,
                               live ? o.live_lattice : nullptr);
        ++stats.ffd_objects;
      }
    }
    const double gpu_ms = ffd_timer.last_ms();
    stats.ffd_ms = gpu_ms < 0.0 ? -1.0 : gpu_ms + (ffd_timer.mode() == GpuTimer::Mode::timer_query ? cpu_ms : 0.0);
  }

  // Draws `mesh` (an object's shown mesh; `range` of its triangles, all when absent): through the FFD vertex shader
  // (variant `variant` of mesh.vert/mesh.frag, its uniforms set by `uniforms`) when `plan` says so, else its
  // MeshBuffers with `base`, which is in use and is left in use.
  template <class Uniforms>
  void draw_object(const std::shared_ptr<const core::TriMesh>& mesh, const detail::FfdPlan& plan,
                   const ShaderProgram& base, const ShaderDefines& variant, const Uniforms& uniforms,
                   std::optional<TriangleRange> range = std::nullopt) {
    const MeshBuffers& b = buffers(mesh);
    if (!plan.vertex) {
      uniforms(base);
      if (range)
        b.draw_range(*range);
      else
        b.draw_triangles();
      return;
    }
    const ShaderProgram& p = plan.vertex->draw_program(variant);
    p.use();
    uniforms(p);
    plan.vertex->draw(p, b, plan.offset, range);
    base.use();
  }

  CachedContactSurface& contact_surface(const std::shared_ptr<const core::FfdBinding>& ffd, const ViewOptions& o) {
    const int cells_u = std::max(o.contact_cells_u, 1), cells_v = std::max(o.contact_cells_v, 1);
    CachedContactSurface& c = contact_cache[ffd.get()];
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

  // Contact surfaces S(u,v) = F(u,v,0) of every visible deformed object: translucent sheets (depth test on, no
  // depth writes, both faces), then their iso-lines. Both are pulled a little towards the eye so they are not
  // lost in z-fighting with the surface they were fitted to.
  void draw_contact_surfaces(const core::Scene& scene, const glm::mat4& view_proj, const glm::vec3& eye,
                             const ViewOptions& o) {
    constexpr float kDepthPull = 0.003f;  // fraction of the eye distance
    std::vector<CachedContactSurface*> todo;
    for (const core::SceneObject& obj : scene.objects())
      if (obj.visible && obj.ffd) todo.push_back(&contact_surface(obj.ffd, o));
    if (todo.empty()) return;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    sheet.use();
    sheet.set("u_view_proj", view_proj);
    sheet.set("u_eye", eye);
    sheet.set("u_depth_pull", kDepthPull);
    sheet.set("u_tint", o.contact_surface_color);
    for (CachedContactSurface* c : todo) {
      c->surface.draw_triangles();
      ++stats.contact_surfaces_drawn;
    }
    pulled_lines.use();
    pulled_lines.set("u_view_proj", view_proj);
    pulled_lines.set("u_eye", eye);
    pulled_lines.set("u_depth_pull", kDepthPull);
    pulled_lines.set("u_point_px", 1.0f);
    pulled_lines.set("u_alpha", 1.0f);
    for (CachedContactSurface* c : todo) {
      if (c->iso_vertices == 0) continue;
      glBindVertexArray(c->iso.vao.id());
      glDrawArrays(GL_LINES, 0, c->iso_vertices);
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }

  void draw_overlay(const std::vector<OverlayVertex>& v, GLenum mode, const ShaderProgram& prog, float alpha) {
    if (v.empty()) return;
    world_stream.upload(v);
    prog.set("u_alpha", alpha);
    glBindVertexArray(world_stream.vao.id());
    glDrawArrays(mode, 0, GLsizei(v.size()));
  }

  // A thick polyline through `px` (viewport pixels, top-left origin), on top (no depth test); nothing when empty.
  void draw_screen_polyline(const std::vector<glm::dvec2>& px, float width_px, const glm::vec4& color,
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

  // DFFD objects' discontinuity planes (F⁻ larger, F⁺ on top, x-ray) and fold-over points (on top of everything);
  // which objects: see ViewOptions::show_discontinuities.
  void draw_dffd(const core::Scene& scene, const ViewOptions& o, const glm::mat4& view_proj) {
    std::vector<OverlayVertex> plane_lines, minus_points, plus_points, folds;
    for (const core::SceneObject& obj : scene.objects()) {
      if (!obj.visible || !obj.dffd) continue;
      const bool selected = !o.selected.empty() && obj.name == o.selected;
      if (o.show_discontinuities && (o.show_lattice || selected))
        append_discontinuity_planes(obj.dffd->lattice, obj.dffd->discontinuities, o.dffd_minus_color,
                                    o.dffd_plus_color, plane_lines, minus_points, plus_points);
      if (o.show_lattice || selected)
        for (const glm::dvec3& p : obj.dffd->fold_points) folds.push_back({glm::vec3(p), o.fold_point_color});
    }
    if (!plane_lines.empty() || !minus_points.empty()) {
      draw_xray(plane_lines, minus_points, view_proj, 1.7f * o.lattice_point_px);
      draw_xray({}, plus_points, view_proj, o.lattice_point_px);
    }
    if (!folds.empty()) {
      points.use();
      points.set("u_view_proj", view_proj);
      points.set("u_point_px", o.fold_point_px);
      glDisable(GL_DEPTH_TEST);
      draw_overlay(folds, GL_POINTS, points, 1.0f);
      glEnable(GL_DEPTH_TEST);
    }
  }

  // Drawn twice: faint where hidden (no depth test), full where visible (x-ray look of modelling tools).
  void draw_xray(const std::vector<OverlayVertex>& lines_v, const std::vector<OverlayVertex>& points_v,
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
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

MeshBuffers& Renderer::buffers_for(const std::shared_ptr<const core::TriMesh>& mesh) { return impl_->buffers(mesh); }
const RenderStats& Renderer::last_stats() const { return impl_->stats; }

void Renderer::release_unused(const core::Scene& scene) {
  impl_->ffd.release_unused(scene);
  impl_->ddm.release_unused(scene);
  std::unordered_set<const core::TriMesh*> live;
  for (const core::SceneObject& o : scene.objects())
    if (o.world_mesh) live.insert(o.world_mesh.get());
  if (impl_->preview) live.insert(impl_->preview.get());
  std::erase_if(impl_->cache, [&](const auto& kv) { return !live.count(kv.first); });
  std::unordered_set<const core::FfdBinding*> live_ffd;
  for (const core::SceneObject& o : scene.objects())
    if (o.ffd) live_ffd.insert(o.ffd.get());
  std::erase_if(impl_->contact_cache, [&](const auto& kv) { return !live_ffd.count(kv.first); });
}

void Renderer::Impl::pass_clear(const Frame& f) {
  const ViewOptions& options = f.options;
  const glm::ivec2 vp = f.vp;
  // Known state: ImGui and others leave theirs behind.
  glViewport(0, 0, vp.x, vp.y);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glEnable(GL_MULTISAMPLE);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearColor(options.background_bottom.x, options.background_bottom.y, options.background_bottom.z, 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void Renderer::Impl::pass_background(const Frame& f) {
  Impl& d = *this;
  const ViewOptions& options = f.options;
  // 1. Background gradient.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  d.background.use();
  d.background.set("u_top", options.background_top);
  d.background.set("u_bottom", options.background_bottom);
  glBindVertexArray(d.empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

SelectedObject Renderer::Impl::pass_objects(const Frame& f) {
  Impl& d = *this;
  const core::Scene& scene = f.scene;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  const glm::vec3& eye = f.eye;
  const glm::vec3& key = f.key;
  const std::vector<detail::FfdPlan>& plans = f.plans;
  // 2. Objects. The selected one writes stencil 1 (outline mask).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_STENCIL_TEST);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  d.mesh.use();
  SelectedObject sel;
  if (options.wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  const std::vector<core::SceneObject>& objects = scene.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const core::SceneObject& o = objects[i];
    const std::shared_ptr<const core::TriMesh>& shown = shown_mesh(o, options);
    if (!o.visible || !shown || shown->empty()) continue;
    const bool is_selected = !options.selected.empty() && o.name == options.selected;
    if (is_selected) {
      sel.object = &o;
      sel.index = i;
    }
    glStencilFunc(GL_ALWAYS, is_selected ? 1 : 0, 0xFF);
    // Surface triangles in the object's colour, then the cut surfaces (inside material) flat in the inside colour.
    const auto shaded = [&](const glm::vec3& albedo, int flat_normal) {
      return [&, albedo, flat_normal](const ShaderProgram& p) {
        p.set("u_view_proj", view_proj);
        p.set("u_eye", eye);
        p.set("u_key_dir", key);
        p.set("u_albedo", albedo);
        p.set("u_highlight", is_selected ? 1.0f : 0.0f);
        p.set("u_flat_normal", flat_normal);
      };
    };
    const MeshBuffers& b = d.buffers(shown);
    d.draw_object(shown, plans[i], d.mesh, {}, shaded(o.color, 0), b.surface_range());
    if (b.inside_range().count > 0)
      d.draw_object(shown, plans[i], d.mesh, {}, shaded(o.inside_color, 1), b.inside_range());
    ++d.stats.objects_drawn;
    d.stats.triangles += b.triangle_count();
  }
  return sel;
}

void Renderer::Impl::pass_wireframe(const Frame& f) {
  const std::vector<core::SceneObject>& objects = f.scene.objects();
  Impl& d = *this;
  const core::Scene& scene = f.scene;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  const std::vector<detail::FfdPlan>& plans = f.plans;
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_STENCIL_TEST);

  // 2b. Wireframe overlay: dark edges over the shaded surfaces.
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  if (options.wireframe) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    d.flat.use();
    const auto flat_uniforms = [&](const ShaderProgram& p) {
      p.set("u_view_proj", view_proj);
      p.set("u_flat_color", glm::vec4(0.05f, 0.05f, 0.06f, 0.45f));
    };
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const std::shared_ptr<const core::TriMesh>& shown = shown_mesh(objects[i], options);
      if (objects[i].visible && shown && !shown->empty())
        d.draw_object(shown, plans[i], d.flat, {{"FLAT_COLOR", ""}}, flat_uniforms);
    }
    d.ddm.draw_flat(scene, options.time_s, view_proj, glm::vec4(0.05f, 0.05f, 0.06f, 0.45f));
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }
}

void Renderer::Impl::pass_grid(const Frame& f) {
  Impl& d = *this;
  const core::Scene& scene = f.scene;
  const core::Camera& camera = f.camera;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  const glm::vec3& eye = f.eye;
  // 3. Ground grid (blended, occluded by meshes, writes no depth).
  if (options.show_grid) {
    glDepthMask(GL_FALSE);
    const float cell = grid_cell_for(scene);
    d.grid.use();
    d.grid.set("u_view_proj", view_proj);
    d.grid.set("u_inv_view_proj", glm::inverse(view_proj));
    d.grid.set("u_eye", eye);
    d.grid.set("u_cell", cell);
    d.grid.set("u_fade_dist", std::max(60.0f * cell, 4.0f * float(glm::length(camera.eye - camera.target))));
    d.grid.set("u_line_color", options.grid_color);
    glBindVertexArray(d.empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
  }
}

void Renderer::Impl::pass_selection_outline(const Frame& f, const SelectedObject& sel) {
  Impl& d = *this;
  const ViewOptions& options = f.options;
  const glm::ivec2 vp = f.vp;
  const glm::mat4& view_proj = f.view_proj;
  const std::vector<detail::FfdPlan>& plans = f.plans;
  // 4. Selection outline: the enlarged silhouette where the object itself is not (stencil != 1), on top.
  if (sel.object) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NOTEQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_DEPTH_TEST);
    d.outline.use();
    d.draw_object(shown_mesh(*sel.object, options), plans[sel.index], d.outline, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}},
                  [&](const ShaderProgram& p) {
                    p.set("u_view_proj", view_proj);
                    p.set("u_viewport", glm::vec2(vp));
                    p.set("u_outline_px", options.outline_px);
                    p.set("u_flat_color", rgba(options.selection_color));
                  });
    d.ddm.draw_outline(*sel.object, options.time_s, view_proj, glm::vec2(vp), options.outline_px,
                       rgba(options.selection_color));
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
  }
}

void Renderer::Impl::pass_lattices_and_contacts(const Frame& f) {
  Impl& d = *this;
  const core::Scene& scene = f.scene;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  const glm::vec3& eye = f.eye;
  // 5. Contact surfaces (translucent, after every opaque mesh), lattices and contact samples on top.
  if (options.show_contact_surface) d.draw_contact_surfaces(scene, view_proj, eye, options);
  if (options.show_lattice || options.show_contact_surface) {
    std::vector<OverlayVertex> lines_v, points_v;
    for (const core::SceneObject& o : scene.objects()) {
      if (!o.visible) continue;
      if (options.show_lattice && o.ffd)
        append_lattice(o.ffd->lattice, {0.45f, 0.78f, 1.0f, 0.9f}, {0.92f, 0.96f, 1.0f, 1.0f}, lines_v, points_v);
      if (options.show_lattice && o.dffd)
        append_lattice(o.dffd->lattice, {0.45f, 0.78f, 1.0f, 0.9f}, {0.92f, 0.96f, 1.0f, 1.0f}, lines_v, points_v);
    }
    d.draw_xray(lines_v, points_v, view_proj, options.lattice_point_px);
    lines_v.clear();
    points_v.clear();
    for (const core::SceneObject& o : scene.objects())
      if (options.show_contact_surface && o.visible && o.placement)
        append_contact_surface(*o.placement, {0.3f, 0.9f, 0.35f, 1.0f}, {0.95f, 0.25f, 0.2f, 1.0f},
                               {0.75f, 0.95f, 0.7f, 0.45f}, lines_v, points_v);
    d.draw_xray(lines_v, points_v, view_proj, options.contact_point_px);
  }
}

void Renderer::Impl::pass_brush(const Frame& f) {
  Impl& d = *this;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  const glm::vec3& eye = f.eye;
  // 5b. The pressing brush: translucent sphere (blended, depth-tested, no depth writes, back faces culled), then
  // the sampled path as points drawn x-ray.
  if (options.brush || !options.brush_path.empty()) {
    std::vector<OverlayVertex> tris, path_v;
    if (options.brush) append_brush_sphere(*options.brush, eye, tris);
    for (const glm::dvec3& p : options.brush_path) path_v.push_back({glm::vec3(p), options.brush_path_color});
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    d.lines.use();
    d.lines.set("u_view_proj", view_proj);
    d.draw_overlay(tris, GL_TRIANGLES, d.lines, 1.0f);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_TRUE);
    d.draw_xray({}, path_v, view_proj, options.contact_point_px);
  }
}

void Renderer::Impl::pass_cut_overlays(const Frame& f) {
  Impl& d = *this;
  const core::Scene& scene = f.scene;
  const ViewOptions& options = f.options;
  const glm::mat4& view_proj = f.view_proj;
  // 5c. DFFD overlays: discontinuity planes and fold-over points (see ViewOptions).
  d.draw_dffd(scene, options, view_proj);
  if (options.incision_lattice) {  // the incision preview's cut lattice and its break at u = 1/2
    const core::TrivariateBSpline<glm::dvec3>& L = *options.incision_lattice;
    std::vector<OverlayVertex> net_lines, net_points, plane_lines, minus_points, plus_points;
    append_lattice(L, {0.45f, 0.78f, 1.0f, 0.6f}, {0.92f, 0.96f, 1.0f, 0.8f}, net_lines, net_points);
    d.draw_xray(net_lines, net_points, view_proj, 0.7f * options.lattice_point_px);
    const std::vector<double>& U = L.knots(0).knots();
    const auto first = std::find(U.begin(), U.end(), 0.5);
    if (options.show_discontinuities && first != U.end() && L.knots(0).multiplicity(0.5) == L.knots(0).order()) {
      core::Discontinuity cut;
      cut.axis = 0;
      cut.u0 = 0.5;
      cut.plus_plane = static_cast<int>(first - U.begin());
      cut.minus_plane = cut.plus_plane - 1;
      append_discontinuity_planes(L, {cut}, options.dffd_minus_color, options.dffd_plus_color, plane_lines,
                                  minus_points, plus_points);
      d.draw_xray(plane_lines, minus_points, view_proj, 1.7f * options.lattice_point_px);
      d.draw_xray({}, plus_points, view_proj, options.lattice_point_px);
    }
  }
}

void Renderer::Impl::pass_screen_overlays(const Frame& f) {
  Impl& d = *this;
  const core::Camera& camera = f.camera;
  const ViewOptions& options = f.options;
  const glm::ivec2 vp = f.vp;
  // 6. The incision tool's generator curve G(v) (projected; split where it passes behind the eye) and the sketched
  // stroke: thick screen-space polylines on top of everything.
  std::vector<glm::dvec2> run;
  for (std::size_t i = 0; i <= options.incision_curve.size(); ++i) {
    const glm::dvec3 p = i < options.incision_curve.size() ? camera.project(options.incision_curve[i]) : glm::dvec3(0.0);
    if (i < options.incision_curve.size() && p.z > 0.0 && std::isfinite(p.x) && std::isfinite(p.y)) {
      run.emplace_back(p.x, p.y);
      continue;
    }
    d.draw_screen_polyline(run, options.incision_curve_px, rgba(options.incision_curve_color), vp);
    run.clear();
  }
  d.draw_screen_polyline(options.stroke_px, options.stroke_width_px, rgba(options.stroke_color), vp);
}

void Renderer::draw(const core::Scene& scene, const core::Camera& camera, const ViewOptions& options) {
  Impl& d = *impl_;
  d.stats = RenderStats{};
  d.stats.timer_mode = d.draw_timer.mode_description();
  Frame f{scene, camera, options, camera.viewport, glm::mat4(camera.projection_matrix() * camera.view_matrix()),
          glm::vec3(camera.eye),
          // Key light: from the camera, raised a little and from the left, so forms read better than a headlight.
          glm::normalize(glm::vec3(-camera.forward() + 0.35 * camera.true_up() - 0.25 * camera.right())),
          {}};

  // 0. FFD evaluation of deformed objects (timed on its own), before any drawing.
  d.preview = options.incision_preview_mesh && !options.incision_preview_mesh->empty() ? options.incision_preview_mesh
                                                                                       : nullptr;
  release_unused(scene);
  d.prepare_ffd(scene, options, f.plans);
  std::optional<GpuTimer::Scope> draw_scope(std::in_place, d.draw_timer);
  const glm::mat4& view_proj = f.view_proj;
  const glm::vec3& eye = f.eye;
  const glm::vec3& key = f.key;

  d.pass_clear(f);
  d.pass_background(f);
  const SelectedObject sel = d.pass_objects(f);
  // 2a. Live DDM layers, shaded like their objects and timed on their own (the draw timer pauses around them).
  const bool any_ddm = detail::DdmDisplay::any_visible(scene);
  if (any_ddm) {
    draw_scope.reset();
    {
      GpuTimer::Scope ddm_scope(d.ddm_timer);
      const detail::DdmDrawn drawn = d.ddm.draw_shaded(scene, options.time_s, view_proj, eye, key, options.selected);
      d.stats.ddm_layers_drawn = drawn.layers;
      d.stats.ddm_vertices = drawn.vertices;
    }
    d.stats.ddm_ms = d.ddm_timer.last_ms();
    draw_scope.emplace(d.draw_timer_b);
  }
  d.pass_wireframe(f);
  d.pass_grid(f);
  d.pass_selection_outline(f, sel);
  d.pass_lattices_and_contacts(f);
  d.pass_brush(f);
  d.pass_cut_overlays(f);
  d.pass_screen_overlays(f);

  // Leave neutral state for the next user of the context (ImGui).
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  draw_scope.reset();
  d.stats.draw_ms = d.draw_timer.last_ms();
  if (any_ddm) {
    const double after = d.draw_timer_b.last_ms();
    d.stats.draw_ms = d.stats.draw_ms < 0.0 || after < 0.0 ? -1.0 : d.stats.draw_ms + after;
  }
  d.stats.cached_meshes = int(d.cache.size());
  d.stats.cached_contact_surfaces = int(d.contact_cache.size());
}

}  // namespace trispline::gpu
