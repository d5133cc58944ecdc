#include "gpu/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <unordered_set>

#include "core/mesh/mesh_io.h"
#include "gpu/render/renderer_impl.h"

namespace trispline::gpu {
namespace detail {

const std::shared_ptr<const core::TriMesh>& shown_mesh(const core::SceneObject& o, const ViewOptions& opt) {
  const std::shared_ptr<const core::TriMesh>* in_place = opt.overlays.mesh_for(o.name);
  return in_place ? *in_place : o.world_mesh;
}

}  // namespace detail

namespace {

using detail::Frame;
using detail::rgba;
using detail::SelectedObject;

// Power of ten a tenth of the scene's size: minor grid cell, world units.
float grid_cell_for(const core::Scene& scene) {
  const core::Aabb b = scene.bounds();
  const double size = b.valid() ? std::max(b.diagonal(), 1e-6) : 2.0;
  return float(std::pow(10.0, std::floor(std::log10(size)) - 1.0));
}

}  // namespace

Renderer::Impl::Impl() {
  world_stream.init(false);
  screen_stream.init(true);
}

detail::CachedMesh& Renderer::Impl::cached(const std::shared_ptr<const core::TriMesh>& m) {
  auto [it, inserted] = cache.try_emplace(m.get());
  if (inserted) {
    it->second.mesh = m;
    it->second.buffers.upload(*m);
    const core::Aabb box = core::mesh_bounds(*m);
    if (box.valid()) it->second.center = glm::vec3(box.center());
    it->second.generation = ++generation;
    ++stats.uploads;
  }
  return it->second;
}

void Renderer::Impl::prepare_ffd(const core::Scene& scene, const ViewOptions& o, std::vector<detail::FfdPlan>& plans) {
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
      if (detail::shown_mesh(obj, o) != obj.world_mesh) continue;                // a mesh in its place: drawn as it is
      if (obj.ffd->params.size() != obj.world_mesh->positions.size()) continue;  // inconsistent: draw world_mesh
      detail::CachedMesh& c = cached(obj.world_mesh);
      const auto* in_place = o.overlays.lattice_for(obj.name);
      const bool live = in_place && (*in_place)->control_counts() == obj.ffd->lattice.control_counts();
      plans[i] = ffd.prepare(obj, {&c.buffers, &c.generation, &c.overwritten, c.mesh.get()}, o.ffd_backend, o.time_s,
                             generation, &stats.ffd_vertices, &cpu_ms, &stats.uploads, live ? *in_place : nullptr);
      ++stats.ffd_objects;
    }
  }
  const double gpu_ms = ffd_timer.last_ms();
  stats.ffd_ms = gpu_ms < 0.0 ? -1.0 : gpu_ms + (ffd_timer.mode() == GpuTimer::Mode::timer_query ? cpu_ms : 0.0);
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

MeshBuffers& Renderer::buffers_for(const std::shared_ptr<const core::TriMesh>& mesh) { return impl_->buffers(mesh); }
const RenderStats& Renderer::last_stats() const { return impl_->stats; }

void Renderer::release_unused(const core::Scene& scene) {
  impl_->ffd.release_unused(scene);
  impl_->ddm.release_unused(scene);
  impl_->volumes.release_unused(scene);
  impl_->textures.release_unused(scene);
  std::unordered_set<const core::TriMesh*> live;
  for (const core::SceneObject& o : scene.objects())
    if (o.world_mesh) live.insert(o.world_mesh.get());
  for (const auto& m : impl_->meshes_in_place) live.insert(m.get());
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
  glClearColor(options.style.background_bottom.x, options.style.background_bottom.y, options.style.background_bottom.z,
               1.0f);
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
  d.background.set("u_top", options.style.background_top);
  d.background.set("u_bottom", options.style.background_bottom);
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
  d.blended.clear();
  SelectedObject sel;
  if (options.wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  const std::vector<core::SceneObject>& objects = scene.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const core::SceneObject& o = objects[i];
    const std::shared_ptr<const core::TriMesh>& shown = detail::shown_mesh(o, options);
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
    if (f.material && ((o.materials && !o.materials->empty()) || o.inside_textured())) {
      d.draw_materials(f, o, i, shown, is_selected);
    } else {
      d.draw_object(shown, plans[i], d.mesh, {}, shaded(o.color, 0), b.surface_range());
      if (b.inside_range().count > 0)
        d.draw_object(shown, plans[i], d.mesh, {}, shaded(o.inside_color, 1), b.inside_range());
    }
    ++d.stats.objects_drawn;
    d.stats.triangles += b.triangle_count();
  }
  d.textures.unbind();
  // Whatever is drawn over the selected object later (tiles, iso-surfaces) takes its pixels out of the mask.
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
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
      const std::shared_ptr<const core::TriMesh>& shown = detail::shown_mesh(objects[i], options);
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
    d.grid.set("u_line_color", options.style.grid_color);
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
  // 4. Selection outline: the enlarged silhouette where the object itself is not (stencil != 1) and where nothing
  // nearer is (depth test, no depth write) — a ring round its visible silhouette, never a fill over objects in front
  // of it (they cleared its stencil).
  if (sel.object) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NOTEQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    d.draw_outline(f, *sel.object, sel.index);
    d.ddm.draw_outline(*sel.object, options.time_s, view_proj, glm::vec2(vp), options.style.outline_px,
                       rgba(options.style.selection_color), d.cached(detail::shown_mesh(*sel.object, options)).center);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_STENCIL_TEST);
  }
}

void Renderer::Impl::pass_ddm_layers(const Frame& f, std::optional<GpuTimer::Scope>& draw_scope) {
  // Shaded like their objects and timed on their own (the draw timer pauses around them).
  if (!detail::DdmDisplay::any_visible(f.scene)) return;
  draw_scope.reset();
  {
    GpuTimer::Scope ddm_scope(ddm_timer);
    const detail::DdmDrawn drawn = ddm.draw_shaded(f.scene, f.options.time_s, f.view_proj, f.eye, f.key,
                                                   f.options.selected, f.options.ddm, f.material ? &textures : nullptr);
    stats.ddm_layers_drawn = drawn.layers;
    stats.ddm_layers_following = drawn.following;
    stats.ddm_vertices = drawn.vertices;
    stats.ddm_instances = drawn.instances;
    stats.ddm_instances_drawn = drawn.instances_drawn;
    stats.ddm_instances_culled = drawn.instances_culled;
    stats.ddm_keep = drawn.keep;
  }
  stats.ddm_ms = ddm_timer.last_ms();
  draw_scope.emplace(draw_timer_b);
}

void Renderer::draw(const core::Scene& scene, const core::Camera& camera, const ViewOptions& options) {
  Impl& d = *impl_;
  d.stats = RenderStats{};
  d.stats.timer_mode = d.draw_timer.mode_description();
  Frame f{scene,
          camera,
          options,
          camera.viewport,
          glm::mat4(camera.projection_matrix() * camera.view_matrix()),
          glm::vec3(camera.eye),
          // Key light: from the camera, raised a little and from the left, so forms read better than a headlight.
          glm::normalize(glm::vec3(-camera.forward() + 0.35 * camera.true_up() - 0.25 * camera.right())),
          {},
          material_shading(scene, options.shading)};

  // 0. FFD evaluation of deformed objects (timed on its own), before any drawing.
  d.meshes_in_place.clear();
  for (const MeshInPlace& m : options.overlays.meshes)
    if (m.mesh && !m.mesh->empty()) d.meshes_in_place.push_back(m.mesh);
  release_unused(scene);
  d.prepare_ffd(scene, options, f.plans);
  const bool any_ddm = detail::DdmDisplay::any_visible(scene);
  const bool any_volume = detail::VolumeDisplay::any_surface(scene);
  std::optional<GpuTimer::Scope> draw_scope(std::in_place, d.draw_timer);

  d.pass_clear(f);
  d.pass_background(f);
  const SelectedObject sel = d.pass_objects(f);
  d.pass_ddm_layers(f, draw_scope);
  d.pass_volumes(f, draw_scope, any_ddm ? d.draw_timer_c : d.draw_timer_b);
  d.pass_blended(f, sel);
  d.pass_wireframe(f);
  d.pass_grid(f);
  d.pass_selection_outline(f, sel);
  d.pass_volume_silhouettes(f);
  d.pass_lattices_and_contacts(f);
  d.pass_discontinuities(f);
  d.pass_world_overlays(f);
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
  // The drawing passes are timed in up to three parts around the DDM and volume passes.
  auto add_part = [&](const GpuTimer& t) {
    const double after = t.last_ms();
    d.stats.draw_ms = d.stats.draw_ms < 0.0 || after < 0.0 ? -1.0 : d.stats.draw_ms + after;
  };
  if (any_ddm || any_volume) add_part(d.draw_timer_b);
  if (any_ddm && any_volume) add_part(d.draw_timer_c);
  d.stats.cached_meshes = int(d.cache.size());
  d.stats.cached_volumes = int(d.volumes.cached());
  d.stats.cached_contact_surfaces = int(d.contact_cache.size());
}

}  // namespace trispline::gpu
