// trispline::gpu::detail::VolumeDisplay — how the Renderer shows the scene's volumes (core::VolumeObject, seed ch. 7):
// each visible volume's iso-surface D = iso ray cast on the spline by a VolumeIsoRenderer (gpu/eval/volume_gl.h; one
// per spline, uploaded once and kept while some volume holds that spline) — or, in dvr mode (volume.render), its
// direct volume rendering through its transfer function, premultiplied — depth-combined with the meshes through
// gl_FragDepth; and its silhouettes (when its settings enable them) as thick screen-space strokes
// (gpu/view/silhouette_strokes.h) in its style and hidden-line mode. ViewOptions::overlays.volumes_in_place replaces a
// volume's iso-level (a live slider) or its silhouettes (extracted for the editor's current view). Internal to the
// renderer (renderer_volume.cpp holds the two passes of Renderer::Impl); not a public API.
#pragma once

#include <cstddef>
#include <memory>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "core/scene/scene.h"
#include "gpu/eval/volume_gl.h"
#include "gpu/view/silhouette_strokes.h"
#include "gpu/view/view_options.h"

namespace trispline::gpu::detail {

// The iso-level and silhouettes a volume is drawn with this frame (its own unless the overlays replace them); the
// silhouettes are null when its settings disable them or none were extracted.
struct ShownVolume {
  double iso = 0.0;
  std::shared_ptr<const core::SilhouetteResult> silhouettes;
  // One per VolumeObject::more_levels entry (null entries draw nothing); empty when silhouettes are off.
  std::vector<std::shared_ptr<const core::SilhouetteResult>> more_silhouettes;
};
ShownVolume shown_volume(const core::VolumeObject& v, const ViewOptions& options);
// The stroke style of `v`'s further level `level` (its own style, and its colour for plain and width strokes).
SilhouetteStrokeStyle level_stroke_style(const core::VolumeObject& v, const core::VolumeIsoLevel& level,
                                         const ViewStyle& style);

// The stroke style of `v`'s silhouettes: its style and hidden mode, ViewStyle's widths, dash and colours; glyphs one
// Newton sub-cell long (a voxel / subdivision, seed §7.3.4), visible runs pulled towards the eye by
// ViewStyle::silhouette_depth_pull × the volume's bounding-box diagonal.
SilhouetteStrokeStyle silhouette_stroke_style(const core::VolumeObject& v, const ViewStyle& style);

// One visible volume's iso-surface, or its direct volume rendering, as drawn this frame.
struct ShownSurface {
  const core::VolumeObject* volume = nullptr;
  double iso = 0.0;       // volume units
  glm::vec3 color{1.0f};  // linear RGB (the selection tint included)
  bool dvr = false;       // through volume->transfer instead of the iso-surface
};

// What VolumeDisplay::update_layer did.
struct LayerUpdate {
  std::size_t cast_pixels = 0;  // pixels whose rays were cast this frame (0: the layer was up to date)
  bool refining = false;        // the layer shows a low-resolution preview in part: later frames refine it
  float scale = 1.0f;           // resolution of the part not refined yet (1 = full)
};

// The iso-surfaces of the visible volumes live in a layer: offscreen colour + depth textures the rays are cast into,
// composited into each frame with its depth (shaders/volume_layer.frag.glsl), so a frame whose view and volumes did
// not change casts nothing. With a time budget (ViewOptions::volume_budget_ms > 0) a cast estimated to exceed it is
// first made at a lower resolution (a preview) and refined at full resolution band by band, top first, over the next
// frames, each within the budget — software GL stays interactive; without one every cast is made whole at once.
class VolumeDisplay {
 public:
  explicit VolumeDisplay(std::shared_ptr<FfdProgramCache> programs) : programs_(std::move(programs)) {}
  // True when some visible volume shows its surface (the renderer then times the ray casting on its own).
  static bool any_surface(const core::Scene& scene);
  // The ray caster of `v`'s spline, uploading it on first use (*uploads counts uploads).
  VolumeIsoRenderer& renderer_for(const core::VolumeObject& v, int* uploads);
  // Brings the layer up to date for this view (view / projection as core::Camera's, viewport in pixels) and these
  // surfaces, within `budget_ms` (≤ 0: whole at once). Binds its own framebuffer; the caller restores its own.
  LayerUpdate update_layer(const std::vector<ShownSurface>& surfaces, const glm::dmat4& view,
                           const glm::dmat4& projection, glm::ivec2 viewport, double budget_ms, int* uploads);
  // Draws the layer into the bound framebuffer with `program` (volume_layer.frag.glsl, in use): depth test on.
  void composite(const ShaderProgram& program, glm::ivec2 viewport, GLuint empty_vao) const;
  // Drops the ray casters of splines no volume of `scene` holds (and the layer, when one was dropped).
  void release_unused(const core::Scene& scene);
  std::size_t cached() const { return cache_.size(); }

 private:
  struct Cached {
    std::shared_ptr<const core::VolumeSpline> spline;  // held so the address cannot be reused by another spline
    std::unique_ptr<VolumeIsoRenderer> gl;
  };
  // Colour (RGBA8, the ray caster's sRGB-encoded output) and depth (32-bit float) textures of one resolution.
  struct Target {
    Framebuffer fbo;
    Texture color, depth;
    glm::ivec2 size{0};
    void ensure(glm::ivec2 size);
  };
  // What the layer holds: the view and every surface's spline, iso-level and colour.
  struct Key {
    glm::dmat4 view{1.0}, projection{1.0};
    glm::ivec2 viewport{0};
    std::vector<std::tuple<const core::VolumeSpline*, double, glm::vec3>> surfaces;
    std::vector<std::pair<core::TransferFunction, double>> dvr;  // per surface: its transfer and step when dvr
    bool operator==(const Key& o) const {
      return view == o.view && projection == o.projection && viewport == o.viewport && surfaces == o.surfaces &&
             dvr == o.dvr;
    }
  };
  // Casts `surfaces` into `t` over rows [row0, row0 + rows) (GL rows, bottom up), cleared there first; returns the
  // wall time (glFinish around it) in ms.
  double cast(Target& t, const std::vector<ShownSurface>& surfaces, const glm::dmat4& view,
              const glm::dmat4& projection, int row0, int rows, int* uploads);

  std::shared_ptr<FfdProgramCache> programs_;
  std::unordered_map<const core::VolumeSpline*, Cached> cache_;
  Target full_, preview_;
  Key key_;
  bool has_key_ = false;
  int refined_rows_ = 0;  // rows of full_ holding the result, from the top
  float preview_scale_ = 1.0f;
  double ms_per_pixel_ = -1.0;  // the last cast's wall time per pixel (negative: not measured yet)
};

}  // namespace trispline::gpu::detail
