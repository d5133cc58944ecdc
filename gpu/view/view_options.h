// trispline::gpu view options — what Renderer::draw is asked to show besides the scene: display switches, a
// style (colours and sizes), and generic overlays that tools and panels fill (editor::Tool::decorate). The renderer
// knows no tool: a stroke being sketched, a pressing brush or an incision preview reach it only as the overlay kinds
// below. Plain data (no GL).
//
// Colours are display (sRGB-encoded) values with alpha; sizes are pixels; positions are world units unless a field
// says viewport pixels (top-left origin, as core::Camera::project returns them).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/dffd/dffd.h"
#include "core/ffd/ffd_evaluator.h"
#include "core/mesh/tri_mesh.h"
#include "core/spline/trivariate_bspline.h"
#include "core/volume/silhouettes.h"

namespace trispline::core {
class Scene;
}

namespace trispline::gpu {

// Colours and sizes of everything the renderer draws on its own (background, grid, selection, lattices, contact
// surfaces, discontinuity planes), and the default look of screen strokes.
struct ViewStyle {
  glm::vec3 background_top{0.23f, 0.23f, 0.25f};
  glm::vec3 background_bottom{0.13f, 0.13f, 0.14f};
  glm::vec3 grid_color{0.55f, 0.55f, 0.58f};
  glm::vec3 selection_color{1.0f, 0.62f, 0.15f};
  float outline_px = 2.0f;
  // Control lattices (ViewOptions::show_lattice): polylines and points.
  glm::vec4 lattice_line_color{0.45f, 0.78f, 1.0f, 0.9f};
  glm::vec4 lattice_point_color{0.92f, 0.96f, 1.0f, 1.0f};
  float lattice_point_px = 7.0f;
  // Contact surface S(u,v) = F(u,v,0) (seed Def. 4): tessellation (u along the stroke), tint (alpha at normal
  // incidence), and iso-lines every contact_iso_every grid lines.
  int contact_cells_u = 48;
  int contact_cells_v = 16;
  glm::vec4 contact_surface_color{0.25f, 0.85f, 0.70f, 0.35f};
  glm::vec4 contact_iso_color{0.0f, 0.78f, 0.64f, 1.0f};
  int contact_iso_every = 4;
  // Contact samples of placed objects (seed §2.3): hits, filled samples, and their sampling grid.
  glm::vec4 contact_hit_color{0.3f, 0.9f, 0.35f, 1.0f};
  glm::vec4 contact_filled_color{0.95f, 0.25f, 0.2f, 1.0f};
  glm::vec4 contact_grid_color{0.75f, 0.95f, 0.7f, 0.45f};
  float contact_point_px = 4.5f;
  // Discontinuity planes (seed §6.3.1 Def. 6): F⁻'s control points larger, F⁺'s on top; fold-over points (seed
  // Theorem 6) big, on top of everything.
  glm::vec4 dffd_minus_color{1.0f, 0.42f, 0.18f, 1.0f};  // warm red-orange
  glm::vec4 dffd_plus_color{0.15f, 0.9f, 1.0f, 1.0f};    // cyan
  glm::vec4 fold_point_color{1.0f, 0.0f, 0.0f, 1.0f};
  float fold_point_px = 14.0f;
  // The usual look of a stroke being drawn over the viewport (ScreenStroke's defaults are these).
  glm::vec4 stroke_color{1.0f, 0.45f, 0.05f, 1.0f};
  float stroke_width_px = 4.0f;
  // Volume silhouettes (seed §7.3.4; gpu/view/silhouette_strokes.h): the thinnest and thickest strokes (the "width"
  // style goes from max at low |∇D| to min at high), the colour of hidden runs ("dashed"), their dash and gap lengths,
  // and how far visible runs are pulled towards the eye for the depth test against meshes, as a fraction of the
  // volume's bounding-box diagonal (the lines lie on the iso-surface they outline, whose own occlusion is the CPU
  // test's).
  float silhouette_width_px = 1.5f;
  float silhouette_max_width_px = 4.0f;
  glm::vec4 silhouette_hidden_color{0.55f, 0.55f, 0.58f, 0.85f};
  float silhouette_dash_px = 5.0f, silhouette_gap_px = 4.0f;
  float silhouette_depth_pull = 0.05f;
};

// A translucent sphere, depth-tested, back faces culled (e.g. a pressing tool's brush, seed §2.4.1).
struct SphereOverlay {
  glm::dvec3 centre{0.0};                      // world units
  double radius = 0.1;                         // world units, > 0
  glm::vec4 color{0.35f, 0.75f, 1.0f, 0.30f};  // alpha at normal incidence (the rim is denser)
};

// Points drawn x-ray: faint where hidden, full where visible.
struct PointsOverlay {
  std::vector<glm::dvec3> points;  // #P × 3, world units
  glm::vec4 color{1.0f};
  float point_px = 4.5f;
};

// A lattice's net drawn like an object's control lattice, with its discontinuity planes in the style's F⁻ / F⁺
// colours when ViewOptions::show_discontinuities is on.
struct LatticeOverlay {
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice;  // world units; null: nothing drawn
  std::vector<core::Discontinuity> discontinuities;  // planes to mark (indices into lattice); may be empty
  glm::vec4 line_color{0.45f, 0.78f, 1.0f, 0.9f};
  glm::vec4 point_color{0.92f, 0.96f, 1.0f, 1.0f};
  float point_px = 7.0f;
};

// A world-space polyline projected and drawn as a thick line on top of everything (split where it passes behind
// the eye).
struct CurveOverlay {
  std::vector<glm::dvec3> points;  // #P × 3, world units
  glm::vec4 color{1.0f};
  float width_px = 3.0f;
};

// A thick polyline in viewport pixels, on top of everything (round joins and caps).
struct ScreenStroke {
  std::vector<glm::dvec2> px;  // #S × 2, viewport pixels, top-left origin
  glm::vec4 color{1.0f, 0.45f, 0.05f, 1.0f};
  float width_px = 4.0f;
};

// A mesh drawn instead of a scene object's world_mesh (shaded, outlined and wireframed as the object; no FFD
// evaluation of that object while set). Uploaded once per mesh pointer, like world meshes.
struct MeshInPlace {
  std::string object;
  std::shared_ptr<const core::TriMesh> mesh;  // world units
};

// A lattice to evaluate a deformed object with instead of its own (a live edit before its command runs): the same
// control counts, orders and knots as the object's FFD lattice, else ignored. Evaluated by ViewOptions::ffd_backend
// (cpu_fast when that is cpu_ref, whose stored world_mesh is stale during the edit).
struct LatticeInPlace {
  std::string object;
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice;
};

// What a volume is drawn with instead of its own iso-level and silhouettes: the Volume panel's live iso-level while
// its slider is dragged, the silhouettes the editor extracted for its current view. Silhouettes are drawn only when
// the volume's silhouette settings are enabled.
struct VolumeInPlace {
  std::string volume;
  std::optional<double> iso;                                  // volume units; none = the volume's own iso
  std::shared_ptr<const core::SilhouetteResult> silhouettes;  // null = the volume's own `silhouettes`
  // One per further level (VolumeObject::more_levels); empty (or another count) = the levels' own silhouettes.
  std::vector<std::shared_ptr<const core::SilhouetteResult>> more_silhouettes;
};

// Triangles with a colour per corner, drawn over the shaded scene — depth-tested against it, pulled a little towards
// the eye so they win over the surface they lie on, blended — e.g. the certified deformation-error heat map. Uploaded
// once per `corners` array (the renderer caches by its address while it is shown).
struct ColoredTrianglesOverlay {
  std::shared_ptr<const std::vector<glm::vec3>> corners;  // #3T, world units
  std::shared_ptr<const std::vector<glm::vec4>> colors;   // #3T, display values with alpha
};

// Segments with a colour each, drawn x-ray like lattices (faint where hidden): e.g. the cells of a fold certificate.
struct ColoredLinesOverlay {
  std::vector<glm::dvec3> ends;   // #2S, world units
  std::vector<glm::vec4> colors;  // #S, display values with alpha
};

// The overlays of one frame, drawn after the scene in this order: spheres, coloured triangles, coloured lines,
// points, lattices, curves, strokes.
struct Overlays {
  std::vector<SphereOverlay> spheres;
  std::vector<PointsOverlay> points;
  std::vector<LatticeOverlay> lattices;
  std::vector<CurveOverlay> curves;
  std::vector<ScreenStroke> strokes;
  std::vector<ColoredTrianglesOverlay> colored_triangles;
  std::vector<ColoredLinesOverlay> colored_lines;
  std::vector<MeshInPlace> meshes;                // the first one naming an object is used
  std::vector<LatticeInPlace> lattices_in_place;  // the first one naming an object is used
  std::vector<VolumeInPlace> volumes_in_place;    // the first one naming a volume is used

  // The mesh drawn for `object` instead of its world_mesh, or null.
  const std::shared_ptr<const core::TriMesh>* mesh_for(const std::string& object) const;
  // The lattice `object` is evaluated with instead of its own, or null.
  const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>* lattice_for(const std::string& object) const;
  // What `volume` is drawn with instead of its own iso-level / silhouettes, or null.
  const VolumeInPlace* volume_for(const std::string& volume) const;
};

// Viewport shading (Blender's Solid / Material Preview, chosen per view in View ▸ Shading). Solid: every object in
// its colour (SceneObject::color), cut surfaces in its inside colour. Material: objects with a MaterialSet drawn with
// their glTF materials (textures, alpha MASK cut-out, BLEND sorted back to front, normal maps;
// gpu/render/material_textures.h); objects without one stay in their colour. Automatic: Material when a visible object
// has a textured material.
enum class Shading { automatic, solid, material };

// The display switches a user toggles (the editor's View menu keeps them as they are).
struct DisplaySwitches {
  Shading shading = Shading::automatic;  // View ▸ Shading
  bool show_lattice = false;             // control lattices of deformed objects (points + polylines)
  bool show_contact_surface = false;     // S(u,v) = F(u,v,0) of deformed objects + contact samples of placed ones
  bool show_grid = true;                 // ground grid on y = 0
  bool wireframe = false;
  // DFFD display (seed §6.3): the discontinuity planes of DFFD objects are drawn when this is on and either
  // show_lattice is on (every DFFD object) or the object is selected (its planes only). The rig's fold points are
  // drawn for the selected object always, and for every DFFD object when show_lattice is on.
  bool show_discontinuities = true;
  // The backend evaluating deformed objects. GLSL compute by default (the editor always has a GL context); replay
  // uses the CPU reference unless told otherwise.
  core::FfdBackend ffd_backend = core::FfdBackend::glsl_compute;
};

// The editor's interactive drawing of large tile layers (gpu/render/renderer_ddm.h, gpu/view/ddm_cull.h). All off — the
// default: replay, recordings and tests — draws every instance of every layer.
struct DdmViewOptions {
  // Leave out instances wholly outside the view frustum or facing away (objects without an FFD, DFFD or clip only).
  bool cull = false;
  double backface_margin_deg = 30.0;  // the facing-away test's margin beyond 90°, degrees; < 0: frustum only
  // While `moving` (the view changed within the last ~0.25 s) draw at most about this many tile vertices: the kept
  // instances thinned to a power-of-two share (1/2, 1/4, …) of them. 0: never thinned.
  bool moving = false;
  std::size_t motion_budget_vertices = 0;
  // With `cull`, the screen-size LOD: pixels one world unit spans at clip w = 1 (projection[1][1] × viewport height
  // ÷ 2), so a tile a few dozen pixels across is drawn from a decimated copy (gpu/view/ddm_cull.h kDdmLodPixels,
  // gpu/eval/ddm_gl.h kDdmLodLevels). 0: every drawn tile at full detail.
  double pixels_per_unit = 0.0;
};

// The editor's motion budgets (DdmViewOptions::motion_budget_vertices): tile vertices a moving frame draws at most on a
// software renderer (llvmpipe: above 10 fps on 2 cores, docs/performance.md) and on a GPU.
inline constexpr std::size_t kDdmMotionBudgetVerticesSoftware = 100'000, kDdmMotionBudgetVertices = 4'000'000;

// True when `shading` draws `scene` with Material shading (Shading::automatic: a visible object has textures).
bool material_shading(const core::Scene& scene, Shading shading);

struct ViewOptions : DisplaySwitches {
  std::string selected;  // highlighted object name (outline colour)
  // The scene time in seconds (a deformed object shows F(E(x) + param_offset + offset_velocity·time_s)).
  double time_s = 0.0;
  // Volume iso-surfaces are ray cast into a layer kept while the view and the volumes stay (renderer_volume.h). > 0:
  // milliseconds one frame may spend casting; a longer cast is shown first at a lower resolution and refined over the
  // next frames (RenderStats::volume_refining). ≤ 0: every cast whole at full resolution (replay, recordings, tests).
  double volume_budget_ms = 0.0;
  DdmViewOptions ddm;
  ViewStyle style;
  Overlays overlays;

  // A stroke in the style's colour and width (the usual way a tool shows the stroke being drawn).
  ScreenStroke& add_stroke(std::vector<glm::dvec2> px);
};

}  // namespace trispline::gpu
