// trispline::gpu::Renderer — draws a core::Scene with OpenGL 4.3 core into the currently bound framebuffer, as
// ViewOptions (gpu/view/view_options.h) asks: display switches, a style and generic overlays. It knows no tool.
// GPU buffers are cached per object and re-uploaded only when the object's world_mesh pointer changes.
// Shaders are .glsl files under gpu/shaders/, embedded at build time. Needs a depth+stencil framebuffer (outline mask).
//
// Look: flat vertical gradient background, studio shading (headlight + hemisphere ambient + rim, gamma-correct
// sRGB output), ground grid on y = 0 fading with distance, selected object tinted and outlined, control lattices,
// contact surfaces S(u,v) = F(u,v,0) (translucent, with iso-lines) and contact samples, then the overlays.
// Deformed objects (SceneObject::ffd) are evaluated for display by ViewOptions::ffd_backend at the object's offset
// at ViewOptions::time_s (renderer_ffd.h): GLSL compute into the drawn buffers, the GLSL vertex path while drawing
// (always for glsl_vertex; for glsl_compute when offset_velocity ≠ 0), the CPU fast path, or the CPU reference
// (world_mesh). Only speed differs between backends.
// Two materials: triangles with TriMesh::face_material = kMaterialInside (DFFD caps, incision walls) are
// drawn with SceneObject::inside_color and flat shading (face normals: untextured, their vertices share the surface's
// normals; in Material shading an inside texture is drawn on them, core::inside_material);
// outline and wireframe cover all triangles. DFFD objects (SceneObject::dffd) are drawn as their world_mesh is (it
// is already split and deformed on the CPU); their lattice, discontinuity planes and fold-over points are overlays
// (ViewOptions::show_discontinuities).
// Live DDM layers (SceneObject::ddm_layers, seed §5.3.2) are drawn by instancing on the GPU at
// ViewOptions::time_s through the object's transform (renderer_ddm.h, gpu/eval/ddm_gl.h), in its colour, wireframe and
// outline included.
// Volumes (Scene::volumes(), seed ch. 7) are drawn as their iso-surfaces D = iso, ray cast on the spline in GLSL
// (gpu/eval/volume_gl.h) and depth-combined with the meshes, with their silhouettes as strokes in the seed's styles
// (renderer_volume.h, gpu/view/silhouette_strokes.h); ViewOptions::overlays.volumes_in_place replaces a volume's
// iso-level or silhouettes for a frame.
#pragma once

#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"
#include "gpu/gl/mesh_buffers.h"
#include "gpu/view/view_options.h"

namespace trispline::gpu {

// What the last draw() did (for tests, the timing overlay and replay's report).
struct RenderStats {
  int objects_drawn = 0;
  std::size_t triangles = 0;
  int uploads = 0;        // meshes (re)uploaded during this draw
  int cached_meshes = 0;  // GPU meshes held after this draw
  int contact_surfaces_drawn = 0;
  int contact_uploads = 0;          // contact-surface tessellations built and uploaded during this draw
  int cached_contact_surfaces = 0;  // held after this draw (one per FfdBinding and tessellation settings)
  int ffd_objects = 0;              // visible deformed objects drawn through the FFD display path
  std::size_t ffd_vertices = 0;     // vertices evaluated during this draw (0 when every result was cached; the
                                    // vertex path evaluates all of its objects' vertices every draw)
  double ffd_ms = 0.0;  // FFD pass (dispatches, uploads, CPU evaluations; the vertex path's evaluation is part of
                        // draw_ms): GpuTimer ms (+ CPU evaluation ms in query mode); 0 without deformed objects,
                        // -1 while the timer has no result yet
  // Live DDM layers (SceneObject::ddm_layers, renderer_ddm.h): layers drawn (with ≥ 1 instance), their vertices
  // (Σ instances × tile vertices, evaluated by the vertex shader every draw), and the shaded layer pass: GpuTimer
  // ms, 0 without layers, -1 while the timer has no result yet (not part of draw_ms).
  int ddm_layers_drawn = 0;
  int ddm_layers_following = 0;  // of those, carried by their object's deformation (FOLLOW variant, ddm_follow.h)
  std::size_t ddm_vertices = 0;
  double ddm_ms = 0.0;
  // With ViewOptions::ddm: the instances of the drawn layers, those drawn, those culled (outside the view or facing
  // away), and the motion LOD's share of the rest (1 = full detail, 0.25 = one in four).
  std::size_t ddm_instances = 0, ddm_instances_drawn = 0, ddm_instances_culled = 0;
  double ddm_keep = 1.0;
  // Volumes (core::Scene::volumes(), renderer_volume.h): visible volumes drawn, ray casters (re)uploaded during this
  // draw and held after it, the iso-surface ray casting pass (GpuTimer ms, 0 without volumes, -1 while the timer has
  // no result yet; not part of draw_ms), and the silhouette points drawn.
  int volumes_drawn = 0;
  int volume_uploads = 0;
  int cached_volumes = 0;
  double volume_ms = 0.0;
  std::size_t volume_cast_pixels = 0;  // rays cast this draw (0: the volume layer was up to date)
  bool volume_refining = false;  // a low-resolution preview is shown in part (ViewOptions::volume_budget_ms): draw
                                 // again to refine it
  float volume_scale = 1.0f;     // resolution of the volume layer's unrefined part (1 = full)
  std::size_t silhouette_points = 0;
  double draw_ms = -1.0;        // the drawing passes (GpuTimer; -1 while unavailable)
  const char* timer_mode = "";  // GpuTimer::mode_description() of the timers above
};

class Renderer {
 public:
  Renderer();  // needs a current GL context; compiles shaders (throws std::runtime_error with the GLSL log)
  ~Renderer();
  // Draws into the bound framebuffer with viewport (0,0,camera.viewport). Clears colour and depth.
  void draw(const core::Scene& scene, const core::Camera& camera, const ViewOptions& options);
  // Forget cached buffers of objects no longer in the scene: meshes no longer any object's world_mesh, contact
  // surfaces whose FfdBinding is no longer any object's ffd (called by draw automatically).
  void release_unused(const core::Scene& scene);

  // GPU buffers of `mesh` (uploaded now if not cached). They stay valid until the cache drops the mesh
  // (it is no longer any object's world_mesh). A GPU evaluator may overwrite positions/normals in place; the
  // renderer draws whatever they hold and re-uploads only when the world_mesh pointer changes.
  MeshBuffers& buffers_for(const std::shared_ptr<const core::TriMesh>& mesh);
  const RenderStats& last_stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// An FBO with colour (RGBA8) and depth attachments, for headless rendering and screenshots.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height, int samples = 4);  // samples > 1: multisampled, resolved on read
  ~OffscreenTarget();
  void bind();  // binds as GL_FRAMEBUFFER and sets the viewport
  int width() const;
  int height() const;
  // RGBA8, #(w·h·4), top row first (ready to write as PNG).
  std::vector<unsigned char> read_rgba();

  int samples() const;         // actual sample count (clamped to GL_MAX_SAMPLES)
  GLuint framebuffer() const;  // the FBO to draw into (multisampled if samples() > 1)
  GLuint resolve();            // resolves MSAA; returns the RGBA8 GL_TEXTURE_2D (e.g. for ImGui::Image)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace trispline::gpu
