// trispline::gpu::Renderer — draws a core::Scene with OpenGL 4.3 core into the currently bound framebuffer.
// GPU buffers are cached per object and re-uploaded only when the object's world_mesh pointer changes.
// Shaders are .glsl files under gpu/shaders/, embedded at build time.
//
// Look: flat vertical gradient background, studio shading (headlight + hemisphere ambient + rim, gamma-correct
// sRGB output), ground grid on y = 0 fading with distance, selected object tinted and outlined, overlays for
// control lattices, contact surfaces S(u,v) = F(u,v,0) (translucent, with iso-lines) and contact samples, and the
// sketched stroke, and the pressing tool's brush sphere with its sampled path (gpu/brush_geometry.h). Needs a depth+stencil framebuffer (outline mask).
// Deformed objects (SceneObject::ffd) are evaluated for display by ViewOptions::ffd_backend at the object's offset
// at ViewOptions::time_s (renderer_ffd.h): GLSL compute into the drawn buffers, the GLSL vertex path while drawing
// (always for glsl_vertex; for glsl_compute when offset_velocity ≠ 0), the CPU fast path, or the CPU reference
// (world_mesh). Only speed differs between backends.
// Two materials: triangles with TriMesh::face_material = kMaterialInside (DFFD caps, incision walls) are
// drawn with SceneObject::inside_color and flat shading (face normals: their vertices share the surface's normals);
// outline and wireframe cover all triangles. DFFD objects (SceneObject::dffd) are drawn as their world_mesh is (it
// is already split and deformed on the CPU); their lattice, discontinuity planes and fold-over points are overlays
// (ViewOptions::show_discontinuities).
// Live DDM layers (SceneObject::ddm_layers, seed §5.3.2) are drawn by instancing on the GPU at
// ViewOptions::time_s through the object's transform (renderer_ddm.h, gpu/ddm_gl.h), in its colour, wireframe and
// outline included.
#pragma once

#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"
#include "gpu/brush_geometry.h"
#include "gpu/mesh_buffers.h"

namespace trispline::gpu {

struct ViewOptions {
  bool show_lattice = false;          // control lattice of deformed objects (points + polylines)
  bool show_contact_surface = false;  // S(u,v) = F(u,v,0) of deformed objects + contact samples of placed ones
  bool show_grid = true;              // ground grid on y = 0
  bool wireframe = false;
  std::string selected;               // highlighted object name (outline colour)
  std::vector<glm::dvec2> stroke_px;  // stroke being sketched, viewport pixels (top-left origin)
  std::optional<BrushSphere> brush;    // pressing tool's sphere under the cursor (translucent, depth-tested)
  std::vector<glm::dvec3> brush_path;  // sphere centres sampled along the press being dragged, world units
  glm::vec4 brush_path_color{1.0f, 0.85f, 0.3f, 1.0f};
  glm::vec3 background_top{0.23f, 0.23f, 0.25f};
  glm::vec3 background_bottom{0.13f, 0.13f, 0.14f};
  // Colours below are display (sRGB-encoded) values; sizes are pixels.
  glm::vec3 grid_color{0.55f, 0.55f, 0.58f};
  glm::vec3 selection_color{1.0f, 0.62f, 0.15f};
  glm::vec3 stroke_color{1.0f, 0.45f, 0.05f};
  float stroke_width_px = 4.0f;
  float outline_px = 2.0f;
  float lattice_point_px = 7.0f;
  float contact_point_px = 4.5f;
  // Contact surface S(u,v) = F(u,v,0): tessellation (u along the stroke), tint (display values, alpha at normal
  // incidence), and iso-lines every contact_iso_every grid lines.
  int contact_cells_u = 48;
  int contact_cells_v = 16;
  glm::vec4 contact_surface_color{0.25f, 0.85f, 0.70f, 0.35f};
  glm::vec4 contact_iso_color{0.0f, 0.78f, 0.64f, 1.0f};
  int contact_iso_every = 4;
  // FFD display: backend evaluating deformed objects, and the scene time in seconds (an object shows
  // F(E(x) + param_offset + offset_velocity·time_s)).
  core::FfdBackend ffd_backend = core::FfdBackend::glsl_compute;
  double time_s = 0.0;
  // Object being edited live (the Press tool's drag preview) and the lattice to show it with instead of its own
  // (same counts, orders, knots): evaluated by ffd_backend through the object's cached evaluator (parameters stay
  // bound; cpu_fast when ffd_backend is cpu_ref, whose stored world_mesh is stale during the edit).
  std::string live_ffd_object;
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> live_lattice;
  // DFFD display (seed §6.3). show_lattice draws a DFFD object's lattice like an FFD lattice. Its
  // discontinuity planes — the control points of F⁻ (Discontinuity::minus_plane along its axis) as larger
  // dffd_minus_color points, those of F⁺ as dffd_plus_color points on top (so coincident, unopened planes show
  // both), and each plane's polylines — are drawn when show_discontinuities is on and either show_lattice is on
  // (every DFFD object) or the object is selected (its planes only, without the rest of the lattice). The rig's
  // fold_points (control points that broke u-monotonicity, seed Theorem 6) are drawn as big fold_point_color points
  // on top of everything for the selected object always, and for every DFFD object when show_lattice is on.
  bool show_discontinuities = true;
  glm::vec4 dffd_minus_color{1.0f, 0.42f, 0.18f, 1.0f};  // warm red-orange (display values)
  glm::vec4 dffd_plus_color{0.15f, 0.9f, 1.0f, 1.0f};    // cyan
  glm::vec4 fold_point_color{1.0f, 0.0f, 0.0f, 1.0f};
  float fold_point_px = 14.0f;
  // Incision tool preview (seed §6.4): the generator curve G(v) (world polyline) drawn as a thick bright
  // line on top of everything, and a whole mesh (world units) drawn instead of object incision_preview_object's
  // world_mesh (no FFD evaluation of that object while set; uploaded once per mesh pointer, like world meshes).
  std::vector<glm::dvec3> incision_curve;
  glm::vec3 incision_curve_color{0.4f, 1.0f, 0.3f};
  float incision_curve_px = 3.0f;
  std::shared_ptr<const core::TriMesh> incision_preview_mesh;
  std::string incision_preview_object;
  // The preview's cut lattice (the opened local lattice of seed Eq. 6.2 with its C⁻¹ break at u = 1/2, world
  // units): its net drawn like a DFFD lattice, its F⁻ / F⁺ planes in dffd_minus_color / dffd_plus_color when
  // show_discontinuities is on. Null: none.
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> incision_lattice;
};

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
  double ffd_ms = 0.0;    // FFD pass (dispatches, uploads, CPU evaluations; the vertex path's evaluation is part of
                          // draw_ms): GpuTimer ms (+ CPU evaluation ms in query mode); 0 without deformed objects,
                          // -1 while the timer has no result yet
  // Live DDM layers (SceneObject::ddm_layers, renderer_ddm.h): layers drawn (with ≥ 1 instance), their vertices
  // (Σ instances × tile vertices, evaluated by the vertex shader every draw), and the shaded layer pass: GpuTimer
  // ms, 0 without layers, -1 while the timer has no result yet (not part of draw_ms).
  int ddm_layers_drawn = 0;
  std::size_t ddm_vertices = 0;
  double ddm_ms = 0.0;
  double draw_ms = -1.0;  // the drawing passes (GpuTimer; -1 while unavailable)
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
