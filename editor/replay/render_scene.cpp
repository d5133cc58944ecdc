#include "editor/replay/render_scene.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "core/commands/anim_record.h"
#include "core/commands/volume_snapshot.h"
#include "core/scene/scene_export.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/gl_context.h"
#include "gpu/render/renderer.h"

namespace trispline::editor {

core::Camera framing_camera(const core::Scene& scene, int width, int height) {
  core::Camera cam;
  cam.viewport = {width > 0 ? width : 1280, height > 0 ? height : 720};
  const core::Aabb box = scene.bounds();
  if (!box.valid()) return cam;
  const glm::dvec3 c = box.center();
  const double radius = std::max(0.5 * box.diagonal(), 1e-6);
  const double dist = radius / std::sin(glm::radians(cam.fov_deg) * 0.5) * 1.05;
  cam.target = c;
  cam.eye = c + glm::normalize(glm::dvec3(0.8, 0.6, 1.0)) * dist;
  cam.near_plane = dist * 0.01;
  cam.far_plane = dist * 10.0;
  return cam;
}

void fit_clip_planes(core::Camera& cam, const core::Scene& scene) {
  // camera.set carries no clip planes: fit them to the scene so meshes in any units are neither clipped nor lose
  // depth precision.
  const core::Aabb box = scene.bounds();
  if (!box.valid()) return;
  const double reach = glm::length(box.center() - cam.eye) + 0.5 * box.diagonal();
  cam.far_plane = std::max(reach * 1.5, 1e-3);
  cam.near_plane = cam.far_plane * 1e-4;
}

core::Camera render_camera(const core::Scene& scene, int width, int height) {
  core::Camera cam = scene.camera_set ? scene.camera : framing_camera(scene, width, height);
  if (width > 0 && height > 0) cam.viewport = {width, height};
  fit_clip_planes(cam, scene);
  return cam;
}

namespace {

// A GL context is current on this thread (the editor's GLFW window, or an EGL context someone made current).
bool context_is_current() { return glfwGetCurrentContext() != nullptr || eglGetCurrentContext() != EGL_NO_CONTEXT; }

// Silhouettes extracted for a render camera, with what they were extracted from.
struct ViewSilhouettes {
  std::shared_ptr<const core::VolumeSpline> spline;
  std::shared_ptr<const core::SingletonTable> table;
  double iso = 0.0;
  core::VolumeSilhouetteSettings settings;
  core::Camera camera;
  std::shared_ptr<const core::SilhouetteResult> result;
  std::vector<double> more_isos;                                    // the further levels'
  std::vector<std::shared_ptr<const core::SilhouetteResult>> more;  // their silhouettes

  static std::vector<double> isos_of(const core::VolumeObject& v) {
    std::vector<double> isos;
    for (const core::VolumeIsoLevel& l : v.more_levels) isos.push_back(l.iso);
    return isos;
  }
  bool serves(const core::VolumeObject& v, const core::Camera& cam) const {
    const auto& a = settings;
    const auto& b = v.silhouette;
    return spline == v.spline && table == v.table && iso == v.iso && more_isos == isos_of(v) && a.hidden == b.hidden &&
           a.projection == b.projection && a.params.subdivision == b.params.subdivision &&
           a.params.accuracy == b.params.accuracy && core::same_view(camera, cam);
  }
};

}  // namespace

struct HeadlessRenderer::Impl {
  std::optional<gpu::HeadlessContext> context;  // declared first: destroyed after the GL objects below
  std::string renderer_name;
  std::optional<gpu::Renderer> renderer;
  std::optional<gpu::OffscreenTarget> target;
  std::map<std::string, ViewSilhouettes> silhouettes;  // by volume name
  double silhouette_ms = 0.0;

  // The volumes' silhouettes for `cam` where the stored ones are for another view, as ViewOptions overrides.
  void view_silhouettes(const core::Scene& scene, const core::Camera& cam, gpu::ViewOptions& view) {
    silhouette_ms = 0.0;
    for (const core::VolumeObject& v : scene.volumes()) {
      if (!v.visible || !v.silhouette.enabled) continue;
      if (v.silhouettes && core::same_view(v.silhouette_camera, cam)) continue;
      ViewSilhouettes& kept = silhouettes[v.name];
      if (!kept.result || !kept.serves(v, cam)) {
        const auto t0 = std::chrono::steady_clock::now();
        const core::VolumeObject posed = core::volume_with_silhouettes(v, cam);  // every level's, for `cam`
        kept = {v.spline, v.table, v.iso, v.silhouette, cam, posed.silhouettes, ViewSilhouettes::isos_of(v), {}};
        for (const core::VolumeIsoLevel& l : posed.more_levels) kept.more.push_back(l.silhouettes);
        silhouette_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      }
      view.overlays.volumes_in_place.push_back({v.name, std::nullopt, kept.result, kept.more});
    }
    std::erase_if(silhouettes, [&](const auto& kv) { return !scene.find_volume(kv.first); });
  }
};

HeadlessRenderer::HeadlessRenderer() : impl_(std::make_unique<Impl>()) {
  if (!context_is_current()) impl_->context.emplace();
  impl_->renderer_name = gpu::current_gl_renderer();
  impl_->renderer.emplace();
}

HeadlessRenderer::~HeadlessRenderer() {
  if (impl_->context) impl_->context->make_current();
  impl_->target.reset();
  impl_->renderer.reset();
}

gpu::RenderStats HeadlessRenderer::draw(const core::Scene& scene, const core::Camera& cam,
                                        const RenderSettings& settings) {
  if (impl_->context) impl_->context->make_current();
  GLint previous_fbo = 0, previous_viewport[4] = {0, 0, 0, 0};
  if (!impl_->context) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
    glGetIntegerv(GL_VIEWPORT, previous_viewport);
  }
  if (!impl_->target || impl_->target->width() != cam.viewport.x || impl_->target->height() != cam.viewport.y) {
    check_frame_size(cam.viewport.x, cam.viewport.y);
    impl_->target.emplace(cam.viewport.x, cam.viewport.y);
  }
  gpu::ViewOptions view;
  view.ffd_backend = settings.ffd_backend;
  view.time_s = settings.time_s;
  view.show_grid = settings.show_grid;
  impl_->view_silhouettes(scene, cam, view);
  impl_->target->bind();
  impl_->renderer->draw(scene, cam, view);
  if (!impl_->context) {
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
    glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
  }
  return impl_->renderer->last_stats();
}

RenderedImage HeadlessRenderer::read_image() {
  if (!impl_->target) throw std::logic_error("HeadlessRenderer::read_image before draw");
  if (impl_->context) impl_->context->make_current();
  GLint previous_fbo = 0;
  if (!impl_->context) glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
  RenderedImage image;
  image.width = impl_->target->width();
  image.height = impl_->target->height();
  image.rgba = impl_->target->read_rgba();
  image.renderer = impl_->renderer_name;
  if (!impl_->context) glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
  return image;
}

void HeadlessRenderer::forget_caches() {
  if (impl_->context) impl_->context->make_current();
  impl_->renderer->release_unused(core::Scene());
}

glm::ivec2 HeadlessRenderer::max_frame_size() const {
  if (impl_->context) impl_->context->make_current();
  GLint renderbuffer = 0, texture = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  return {std::min({renderbuffer, texture, viewport[0]}), std::min({renderbuffer, texture, viewport[1]})};
}

void HeadlessRenderer::check_frame_size(int width, int height) const {
  const glm::ivec2 max = max_frame_size();
  if (width < 1 || height < 1 || width > max.x || height > max.y)
    throw std::runtime_error("a frame of " + std::to_string(width) + "×" + std::to_string(height) +
                             " pixels is larger than this GL implementation draws (" + impl_->renderer_name +
                             ": GL_MAX_RENDERBUFFER_SIZE / GL_MAX_VIEWPORT_DIMS allow " + std::to_string(max.x) + "×" +
                             std::to_string(max.y) + ")");
  if (std::int64_t(width) * height > core::kMaxRecordPixels)
    throw std::runtime_error("a frame of " + std::to_string(width) + "×" + std::to_string(height) +
                             " pixels is over the 64-megapixel budget of an offscreen frame (8192×8192)");
}

double HeadlessRenderer::last_silhouette_ms() const { return impl_->silhouette_ms; }
const std::string& HeadlessRenderer::renderer() const { return impl_->renderer_name; }
bool HeadlessRenderer::owns_context() const { return impl_->context.has_value(); }

RenderedImage render_scene_headless(const core::Scene& document, int width, int height,
                                    const RenderSettings& settings) {
  const core::Scene rendered = core::render_visible_scene(document);  // what renders show (object.visibility)
  // Objects the renderer cannot animate (glTF clips, DFFD splits) are evaluated on the CPU at the requested time.
  bool cpu_animated = false;
  for (const core::SceneObject& o : rendered.objects()) cpu_animated = cpu_animated || o.cpu_animated();
  const core::Scene scene = cpu_animated ? core::scene_with_posed_clips(rendered, settings.time_s) : rendered;
  HeadlessRenderer headless;
  const core::Camera cam = render_camera(scene, width, height);
  auto draw = [&] { return headless.draw(scene, cam, settings); };
  // Frame 1 builds shader programs and uploads everything. Dropping the caches makes frame 2 what the editor's first
  // frame after a command does (upload, bind, evaluate) without the one-time program builds: its FFD pass is
  // reported. Frame 3 is a steady frame (cached evaluation; GPU timer queries of frame 2 have answered after the
  // glFinish): its draw pass is reported.
  draw();
  const double silhouette_ms = headless.last_silhouette_ms();  // the later frames reuse what this one extracted
  headless.forget_caches();
  const gpu::RenderStats warm = draw();
  glFinish();
  const gpu::RenderStats steady = draw();
  RenderTimings t;
  t.ffd_objects = warm.ffd_objects;
  t.ffd_vertices = warm.ffd_vertices;
  // Wall-clock timers measure each frame exactly; query timers report the newest answered query, frame 2's by now.
  t.ffd_ms = gpu::is_software_renderer() ? warm.ffd_ms : steady.ffd_ms;
  t.draw_ms = steady.draw_ms;
  // The vertex-shader path evaluates while drawing; GLSL compute hands animated objects to it
  // (gpu/render/renderer_ffd.h).
  bool animated = false;
  for (const core::SceneObject& o : scene.objects()) animated = animated || (o.visible && o.animated());
  t.ffd_in_draw = settings.ffd_backend == core::FfdBackend::glsl_vertex ||
                  (settings.ffd_backend == core::FfdBackend::glsl_compute && animated);
  t.timer_mode = steady.timer_mode ? steady.timer_mode : "";
  t.volumes = steady.volumes_drawn;
  // The ray casting of frame 2 (the layer is cast there and only composited in frame 3), as for the FFD pass.
  t.volume_ms = steady.volumes_drawn > 0 ? (gpu::is_software_renderer() ? warm.volume_ms : steady.volume_ms) : -1.0;
  t.silhouettes = steady.silhouette_points;
  t.silhouette_ms = silhouette_ms;
  RenderedImage image = headless.read_image();
  image.timings = std::move(t);
  return image;
}

BackendGeometry evaluate_with_backend(const core::Scene& scene, core::FfdBackend backend, double time_s) {
  if (!std::isfinite(time_s)) throw std::invalid_argument("scene time is not finite");
  std::optional<gpu::HeadlessContext> context;
  BackendGeometry out;
  if (core::is_gpu_backend(backend)) {
    context.emplace();
    out.renderer = context->renderer();
  }
  const auto t0 = std::chrono::steady_clock::now();
  out.scene = scene;
  std::vector<glm::dvec3> positions, normals;
  for (const core::SceneObject& object : scene.objects()) {
    if (!object.ffd || !object.world_mesh) continue;
    const core::FfdBinding& binding = *object.ffd;
    const core::TriMesh rest = object.world_rest_mesh();
    std::unique_ptr<core::FfdEvaluator> eval =
        core::is_gpu_backend(backend) ? gpu::make_gl_ffd_evaluator(backend) : core::make_cpu_ffd_evaluator(backend);
    eval->bind_vertices(binding.params, rest.normals);
    eval->set_lattice(binding.lattice, binding.embedding);
    eval->evaluate(object.offset_at(time_s));
    eval->read_results(positions, normals);
    core::TriMesh mesh = *object.world_mesh;
    if (positions.size() != mesh.positions.size())
      throw std::runtime_error("FFD backend " + std::string(core::to_string(backend)) + " returned " +
                               std::to_string(positions.size()) + " positions for '" + object.name + "' (" +
                               std::to_string(mesh.positions.size()) + " vertices)");
    mesh.positions = positions;
    if (normals.size() == mesh.positions.size()) mesh.normals = normals;
    core::SceneObject moved = object;
    moved.param_offset = object.offset_at(time_s);
    moved.world_mesh = std::make_shared<const core::TriMesh>(std::move(mesh));
    out.scene.replace(std::move(moved));
    ++out.objects;
    out.vertices += positions.size();
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace trispline::editor
