// trispline::gpu::Renderer::Impl — the renderer's caches, programs and passes, shared by renderer.cpp (the scene
// passes) and renderer_overlays.cpp (lattices, contact surfaces, discontinuity planes and ViewOptions::overlays).
// Internal to gpu/: not installed, not included outside it.
#pragma once

#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "gpu/gl/shader_program.h"
#include "gpu/gl/timer.h"
#include "gpu/render/material_textures.h"
#include "gpu/render/renderer.h"
#include "gpu/render/renderer_ddm.h"
#include "gpu/render/renderer_ffd.h"
#include "gpu/render/renderer_volume.h"
#include "gpu/view/overlay_geometry.h"

namespace trispline::gpu::detail {

struct CachedMesh {
  std::shared_ptr<const core::TriMesh> mesh;  // held so the address cannot be reused by another mesh
  MeshBuffers buffers;
  std::uint64_t generation = 0;  // changes whenever the buffers' contents change (upload, FFD write)
  bool overwritten = false;      // the buffers hold an FFD evaluation rather than world_mesh
  glm::vec3 center{0.0f};        // centre of the mesh's bounds, world units (orders blended objects)
};

// A BLEND material's triangles of one object, drawn after the opaque scene (back to front by `distance`).
struct BlendedRange {
  std::size_t object = 0;  // index into Scene::objects()
  MaterialRange range;
  float distance = 0.0f;  // eye to the object's mesh centre, world units
};

// A growable stream buffer for per-frame overlay geometry (small: lattices, contact grids, strokes).
struct StreamBuffer {
  VertexArray vao;
  Buffer vbo;
  GLsizeiptr capacity = 0;
  void init(bool screen_space);
  void upload(const std::vector<OverlayVertex>& v);
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

// A ColoredTrianglesOverlay on the GPU (OverlayVertex GL_TRIANGLES), uploaded once.
struct CachedColoredTriangles {
  std::shared_ptr<const std::vector<glm::vec3>> corners;  // held so the address cannot be reused
  std::shared_ptr<const std::vector<glm::vec4>> colors;
  StreamBuffer buffer;
  GLsizei vertices = 0;
  bool used = false;  // shown in the current draw (others are dropped after it)
};

// What every pass of Renderer::draw reads: the scene, the view and its matrices, the FFD plan per object.
struct Frame {
  const core::Scene& scene;
  const core::Camera& camera;
  const ViewOptions& options;
  glm::ivec2 vp;               // viewport, pixels
  glm::mat4 view_proj;         // world → clip
  glm::vec3 eye;               // world units
  glm::vec3 key;               // unit key-light direction
  std::vector<FfdPlan> plans;  // per scene object
  bool material = false;       // Material shading (ViewOptions::shading, material_shading())

  const ViewStyle& style() const { return options.style; }
};

// The selected object (it writes stencil 1 for the outline), when it was drawn.
struct SelectedObject {
  const core::SceneObject* object = nullptr;
  std::size_t index = 0;
};

inline glm::vec4 rgba(const glm::vec3& c, float a = 1.0f) { return {c, a}; }

// The mesh drawn for `o`: the overlay mesh in its place when the options name `o`, else its world_mesh.
const std::shared_ptr<const core::TriMesh>& shown_mesh(const core::SceneObject& o, const ViewOptions& opt);

}  // namespace trispline::gpu::detail

namespace trispline::gpu {

struct Renderer::Impl {
  // The passes of Renderer::draw, in order; each leaves the GL state the next expects.
  void pass_clear(const detail::Frame& f);       // known state (ImGui leaves its own), cleared to the background
  void pass_background(const detail::Frame& f);  // 1. the background gradient
  detail::SelectedObject pass_objects(const detail::Frame& f);  // 2. shaded objects; the selected one: stencil 1
  void pass_ddm_layers(const detail::Frame& f, std::optional<GpuTimer::Scope>& draw_scope);  // 2a. live DDM layers
  // 2a'. iso-surfaces, timed by volume_timer; the draw timer resumes with `resume`
  void pass_volumes(const detail::Frame& f, std::optional<GpuTimer::Scope>& draw_scope, GpuTimer& resume);
  void pass_blended(const detail::Frame& f, const detail::SelectedObject& sel);  // 2a''. BLEND materials, sorted
  void pass_wireframe(const detail::Frame& f);  // 2b. dark edges over the shaded surfaces
  void pass_grid(const detail::Frame& f);       // 3. the ground grid
  void pass_selection_outline(const detail::Frame& f, const detail::SelectedObject& sel);  // 4. selection outline
  void pass_volume_silhouettes(const detail::Frame& f);     // 4b. volume silhouettes; the selected volume's box
  void pass_lattices_and_contacts(const detail::Frame& f);  // 5. contact surfaces, lattices, contact samples
  void pass_discontinuities(const detail::Frame& f);        // 5b. DFFD planes and fold-overs
  void pass_world_overlays(const detail::Frame& f);         // 6. overlay spheres, points and lattices
  void pass_screen_overlays(const detail::Frame& f);        // 7. overlay curves and strokes, on top

  ShaderProgram background{{"background.vert.glsl", "background.frag.glsl"}};
  ShaderProgram mesh{{"mesh.vert.glsl", "mesh.frag.glsl"}};
  ShaderProgram flat{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"FLAT_COLOR", ""}}};
  ShaderProgram outline{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}}};
  ShaderProgram material{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"MATERIAL", ""}}};
  ShaderProgram outline_mask{{"mesh.vert.glsl", "mesh.frag.glsl"},
                             {{"OUTLINE", ""}, {"FLAT_COLOR", ""}, {"MATERIAL", ""}, {"ALPHA_MASK", ""}}};
  ShaderProgram grid{{"grid.vert.glsl", "grid.frag.glsl"}};
  ShaderProgram lines{{"lines.vert.glsl", "lines.frag.glsl"}};
  ShaderProgram points{{"lines.vert.glsl", "lines.frag.glsl"}, {{"ROUND_POINTS", ""}}};
  ShaderProgram screen{{"lines.vert.glsl", "lines.frag.glsl"}, {{"SCREEN_SPACE", ""}}};
  ShaderProgram volume_layer{{"background.vert.glsl", "volume_layer.frag.glsl"}};
  ShaderProgram screen_depth{{"lines.vert.glsl", "lines.frag.glsl"}, {{"SCREEN_SPACE", ""}, {"SCREEN_DEPTH", ""}}};
  ShaderProgram sheet{{"mesh.vert.glsl", "mesh.frag.glsl"}, {{"DEPTH_PULL", ""}, {"TRANSLUCENT", ""}}};
  ShaderProgram pulled_lines{{"lines.vert.glsl", "lines.frag.glsl"}, {{"DEPTH_PULL", ""}}};
  VertexArray empty_vao = VertexArray::create();  // attribute-less full-screen passes
  detail::StreamBuffer world_stream, screen_stream;
  std::unordered_map<const core::TriMesh*, detail::CachedMesh> cache;
  MaterialTextures textures;
  std::vector<detail::BlendedRange> blended;  // filled by pass_objects, drawn by pass_blended
  std::unordered_map<const core::FfdBinding*, detail::CachedContactSurface> contact_cache;
  std::unordered_map<const std::vector<glm::vec3>*, detail::CachedColoredTriangles> colored_cache;
  std::shared_ptr<FfdProgramCache> ffd_programs = std::make_shared<FfdProgramCache>();
  detail::FfdDisplay ffd{ffd_programs};
  detail::DdmDisplay ddm{ffd_programs};
  GpuTimer ddm_timer, draw_timer_b;  // the DDM pass; the drawing passes after it (timers cannot nest)
  detail::VolumeDisplay volumes{ffd_programs};
  GpuTimer volume_timer, draw_timer_c;  // the iso-surface pass; the drawing passes after it (after DDM: timer c)
  std::uint64_t generation = 0;         // source of CachedMesh::generation values
  GpuTimer ffd_timer, draw_timer;
  RenderStats stats;
  // The meshes drawn in place of objects during the current draw (kept cached while they are shown).
  std::vector<std::shared_ptr<const core::TriMesh>> meshes_in_place;

  Impl();

  detail::CachedMesh& cached(const std::shared_ptr<const core::TriMesh>& m);
  MeshBuffers& buffers(const std::shared_ptr<const core::TriMesh>& m) { return cached(m).buffers; }

  // FFD pass: brings every visible deformed object's display up to date; plans[i] says how to draw object i.
  void prepare_ffd(const core::Scene& scene, const ViewOptions& o, std::vector<detail::FfdPlan>& plans);

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

  // Material shading of object `i` (`o`, drawing `shown`): one draw per material range — opaque and MASK ones now,
  // BLEND ones queued in `blended`, cut surfaces textured (core::inside_material) or else, like slots without a
  // material, in the Solid look. Leaves `mesh` in use.
  void draw_materials(const detail::Frame& f, const core::SceneObject& o, std::size_t i,
                      const std::shared_ptr<const core::TriMesh>& shown, bool selected);
  // One material range of object `i` with the MATERIAL program (textures bound, culled unless double sided).
  // `set` holds m's images; flat_normal 1: face normals (cut surfaces).
  void draw_material_range(const detail::Frame& f, std::size_t i, const std::shared_ptr<const core::TriMesh>& shown,
                           const core::Material& m, const core::MaterialSet& set, TriangleRange range, bool selected,
                           int flat_normal = 0);
  // The selection outline of `o`'s shown mesh: the enlarged silhouette, its MASK ranges cut out by their alpha.
  void draw_outline(const detail::Frame& f, const core::SceneObject& o, std::size_t i);

  detail::CachedContactSurface& contact_surface(const std::shared_ptr<const core::FfdBinding>& ffd,
                                                const ViewStyle& style);
  // Contact surfaces S(u,v) = F(u,v,0) of every visible deformed object: translucent sheets, then their iso-lines.
  void draw_contact_surfaces(const detail::Frame& f);
  // `v` with `prog` (in use, u_view_proj set) from the world stream, at `alpha`; nothing when empty.
  void draw_overlay(const std::vector<OverlayVertex>& v, GLenum mode, const ShaderProgram& prog, float alpha);
  // A thick polyline through `px` (viewport pixels, top-left origin), on top (no depth test); nothing when empty.
  void draw_screen_polyline(const std::vector<glm::dvec2>& px, float width_px, const glm::vec4& color,
                            const glm::ivec2& vp);
  // Drawn twice: faint where hidden (no depth test), full where visible (x-ray look of modelling tools).
  void draw_xray(const std::vector<OverlayVertex>& lines_v, const std::vector<OverlayVertex>& points_v,
                 const glm::mat4& view_proj, float point_px);
  // `planes` of `lattice`: their polylines and F⁻ points (larger), then F⁺ points on top, x-ray.
  void draw_discontinuity_planes(const core::TrivariateBSpline<glm::dvec3>& lattice,
                                 const std::vector<core::Discontinuity>& planes, const detail::Frame& f);
};

}  // namespace trispline::gpu
