// Headless rendering of a scene (replay's final.png, README screenshots) through an EGL surfaceless context, and
// the deformed geometry as a chosen FFD backend computes it (replay --ffd-backend: scene.glb from the GPU path).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"
#include "gpu/render/renderer.h"

namespace trispline::editor {

// How the scene is drawn: gpu::ViewOptions::ffd_backend, ::time_s and ::show_grid.
struct RenderSettings {
  core::FfdBackend ffd_backend = core::FfdBackend::cpu_ref;
  double time_s = 0;      // scene time, seconds (animated objects, lattice.animate_offset)
  bool show_grid = true;  // the viewport's ground grid (recordings leave it out, as a render does)
};

// gpu::RenderStats of the frame that made the image (replay's report.json timings.render).
struct RenderTimings {
  int ffd_objects = 0;           // deformed objects evaluated by the renderer's FFD pass
  std::size_t ffd_vertices = 0;  // their vertices
  double ffd_ms = -1;            // FFD pass, ms (GPU timer; negative = not measured)
  double draw_ms = -1;           // scene draw, ms (GPU timer; negative = not measured)
  bool ffd_in_draw = false;      // glsl_vertex: the evaluation is part of draw_ms (see ui::PassTimings)
  int volumes = 0;               // volumes whose iso-surface was ray cast
  double volume_ms = -1;         // the ray casting pass of a frame that casts (the volume layer: cast, composited),
                                 // ms (GPU timer; negative = not measured or no volume)
  std::size_t silhouettes = 0;   // silhouette points drawn
  double silhouette_ms = 0;      // CPU wall time extracting silhouettes for the render camera (0: none needed)
  std::string timer_mode;        // gpu::GpuTimer::describe() of the timers used
};

struct RenderedImage {
  int width = 0, height = 0;        // pixels
  std::vector<unsigned char> rgba;  // #(w·h·4), top row first
  std::string renderer;             // GL_RENDERER of the context used
  RenderTimings timings;
};

// A camera that frames the visible objects from the front-right-above, for scenes without camera.set.
core::Camera framing_camera(const core::Scene& scene, int width, int height);

// The camera a headless image uses: the scene's camera (framing_camera when none was set), its viewport replaced by
// width×height when both are > 0, and its clip planes fitted to the scene's bounds (camera.set carries none).
core::Camera render_camera(const core::Scene& scene, int width = 0, int height = 0);
// Sets camera.near_plane/far_plane so that every visible object of `scene` lies between them (unchanged when the
// scene has no bounds).
void fit_clip_planes(core::Camera& camera, const core::Scene& scene);

// A persistent headless renderer for many images (anim.record's frames): one GL context, one gpu::Renderer with its
// shader programs built once, one offscreen target per size. The context is a private EGL surfaceless one, or —
// when a GL context is already current on the calling thread at construction (the editor's window) — that one;
// every call must then be made with that context current, and the previous framebuffer binding and viewport are
// restored after each draw. Throws gpu::GlContextError / std::runtime_error from the constructor.
class HeadlessRenderer {
 public:
  HeadlessRenderer();
  ~HeadlessRenderer();
  HeadlessRenderer(const HeadlessRenderer&) = delete;
  HeadlessRenderer& operator=(const HeadlessRenderer&) = delete;

  // Draws one frame of `scene` seen by `camera` into a camera.viewport-sized target (4× MSAA) and returns its stats.
  // A volume whose silhouettes are enabled but were extracted for another view (core::same_view) is drawn with
  // silhouettes extracted for `camera` (CPU, deterministic; kept while the volume, its settings and the view stay).
  gpu::RenderStats draw(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings);
  // CPU wall time of the silhouette extractions of the last draw, ms (0 when the stored ones or the kept ones served).
  double last_silhouette_ms() const;
  // Pixels of the last draw (top row first) with renderer() filled in; timings left empty.
  RenderedImage read_image();
  // Drops every cached GPU buffer, so the next draw uploads all it draws and depends on nothing drawn before.
  void forget_caches();
  // The largest frame this GL implementation draws: min of GL_MAX_RENDERBUFFER_SIZE, GL_MAX_TEXTURE_SIZE and
  // GL_MAX_VIEWPORT_DIMS, pixels.
  glm::ivec2 max_frame_size() const;
  // Throws std::runtime_error naming the limit when a width × height frame exceeds max_frame_size() or
  // core::kMaxRecordPixels. draw() calls it before allocating a target.
  void check_frame_size(int width, int height) const;
  const std::string& renderer() const;  // GL_RENDERER
  bool owns_context() const;            // false: drawing with the context that was current at construction

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Renders the render-visible objects and volumes (core::render_visible_scene: object.visibility's `render`) with the
// scene's camera (or framing_camera of them when none was set). width/height 0 = the camera's viewport;
// otherwise the camera's viewport is replaced (aspect follows). Throws gpu::GlContextError / std::runtime_error.
// Three frames are drawn: timings.ffd_* are those of a frame that uploads and evaluates with shader programs already
// built (as the editor's first frame after a command), draw_ms that of a steady frame; the image is the last frame.
RenderedImage render_scene_headless(const core::Scene& scene, int width = 0, int height = 0,
                                    const RenderSettings& settings = {});

// What evaluate_with_backend() did.
struct BackendGeometry {
  core::Scene scene;         // a copy whose deformed objects' world meshes come from the backend
  int objects = 0;           // deformed objects evaluated
  std::size_t vertices = 0;  // their vertices
  double ms = 0;             // wall time: bind + set_lattice (program builds) + evaluate + read back, all objects
  std::string renderer;      // GL_RENDERER for GLSL backends, "" for CPU ones
};

// Every deformed object of `scene` evaluated at scene time `time_s` (offset SceneObject::offset_at) by `backend`
// through the core::FfdEvaluator contract, read back to the host; positions and normals replace the world mesh's
// (topology, uvs, names and colours kept). For GLSL backends a headless GL context is made for the duration.
// Throws std::invalid_argument (e.g. an order the backend does not support), gpu::GlContextError, std::runtime_error.
BackendGeometry evaluate_with_backend(const core::Scene& scene, core::FfdBackend backend, double time_s = 0);

}  // namespace trispline::editor
