// trispline::editor::DdmPaintTool — the "Tile Paint" tool (seed ch. 5, deformation displacement
// maps): a brush that paints geometric tiles onto an object's surface. A circle of radius_px viewport pixels follows
// the cursor over the viewport ([ and ] shrink / grow it, as Blender's brush radius); left-drag collects one stroke in
// viewport pixels (top-left origin) of the view at mouse-down, shown as the brush's swath; on mouse-up the tool
// executes ONE `ddm.paint` (core/commands/ddm_paint.h) on the chosen object and layer, carrying that view as
// "camera". A click is a dab (a one-point stroke). Ctrl held at mouse-down erases (Blender's invert), as does the
// panel's Erase toggle (Ctrl then paints).
// The panel picks the object (follows the selection), the layer (one of the object's layers, or a new one, made by
// the first stroke or by Fill with the panel's tile / layout / tile size or counts / height / base — base and tile size
// defaulting per object, ddm_default_base), the tiles and tile vertices Fill would make, the brush radius and the
// erase toggle; Fill submits `ddm.fill` for the whole surface, Bake `ddm.bake` (a mesh object named
// "<object>.<layer>"). Fill and Bake are built on a worker thread behind a progress bar with Cancel
// (ToolContext::background); strokes run through ToolContext::defer (a "Working…" frame first); errors go to the Log
// panel and leave the scene as it was.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/commands/ddm_paint.h"
#include "editor/tools/stroke_gesture.h"
#include "editor/tools/tool.h"
#include "ui/ddm_anim_panel.h"
#include "ui/param_widgets.h"

namespace trispline::editor {

// The panel's values. `paint` is the next ddm.paint's params but the stroke's own (object, stroke, camera, erase are
// set per stroke): the layer (an existing layer of the object, or the name of a new one), the new layer's fields
// (also Fill's; ddm.paint ignores them when the layer exists), the brush radius and the Erase toggle (Ctrl at
// mouse-down inverts it).
struct DdmPaintToolParams {
  core::DdmPaintParams paint = [] {
    core::DdmPaintParams p;
    p.layer = "tiles";
    p.radius_px = 40.0;
    return p;
  }();
  bool own_color = false;                // give a new layer its own colour (spec.color; else it takes the object's)
  glm::vec3 color{0.80f, 0.62f, 0.20f};  // that colour, linear RGB in [0,1], kept while own_color is off
};

// The ddm.paint line of `stroke_px` (#S × 2 viewport pixels): "camera" when `view` is given, the new layer's fields
// (with "color" when own_color) when `new_layer`.
nlohmann::json ddm_paint_line(const std::string& object, const std::vector<glm::dvec2>& stroke_px,
                              const DdmPaintToolParams& params, bool erase, bool new_layer,
                              const std::optional<core::Camera>& view = std::nullopt);
// The panel's first tile size for an object: a tenth of its rest mesh's bounding-box diagonal, to two significant
// figures (1 without an object), world units.
double ddm_default_tile_size(const core::SceneObject* o);
// The Height field's default for `o`: a third of ddm_default_tile_size, to two significant digits (world units).
double ddm_default_tile_height(const core::SceneObject* o);
// The ddm.fill line of the panel's values (the whole surface; a layer of that name is replaced).
nlohmann::json ddm_fill_line(const std::string& object, const DdmPaintToolParams& params);

class DdmPaintTool : public Tool {
 public:
  static constexpr double kMinRadiusPx = 2.0, kMaxRadiusPx = 500.0;
  // Fill asks first above this many tile vertices (the estimate): a software GL (llvmpipe) draws ~1 M tile vertices
  // at a few frames per second, a GPU several times more.
  static constexpr std::size_t kAskFillVertices = 4'000'000, kAskFillVerticesSoftware = 1'000'000;

  ui::ToolEntry entry() const override;
  void activate(ToolContext& ctx) override;
  void deactivate(ToolContext& ctx) override;
  void handle_input(const ToolInput& in, ToolContext& ctx) override;
  void mouse_away() override;
  void draw_panel(ToolContext& ctx) override;
  void decorate(gpu::ViewOptions& options) const override;
  std::string hint() const override;
  bool owns_mouse() const override { return gesture_.drawing(); }

  const DdmPaintToolParams& params() const { return params_; }
  // Sets the panel's values; they then stay as given (no per-object defaults when the object changes).
  void set_params(const DdmPaintToolParams& p) { params_ = p, defaults_for_ = "\x01given"; }
  void set_object(const std::string& name) { object_ = followed_selection_ = name; }
  const std::string& object() const { return object_; }
  // True when the object has no layer called params().layer (the next stroke or Fill makes it).
  bool new_layer(const ToolContext& ctx) const;
  // Multiplies the brush radius by `factor`, clamped to [kMinRadiusPx, kMaxRadiusPx] ([ = 1/1.15, ] = 1.15).
  void scale_radius(double factor);

  const std::vector<glm::dvec2>& stroke() const { return gesture_.points(); }  // pixels of the drag under way
  bool erasing() const { return erasing_; }                                    // the drag under way erases
  const std::optional<glm::dvec2>& hover() const { return hover_; }            // brush centre, viewport pixels
  // Draws the brush circle (and the swath of the drag under way) into ImGui's background draw list, over the 3-D
  // view and under the panels; called from handle_input while an ImGui frame is open.
  void draw_brush() const;

  // The commands the panel's buttons submit (also for tests): ddm.fill of the whole surface, ddm.bake of the layer.
  void fill(ToolContext& ctx);
  void bake(ToolContext& ctx);
  void remove_layer(ToolContext& ctx);  // ddm.remove of the layer
  // ddm.export of `object`'s `layer`: its "positions" or "normals" map as the PNG `file` (absolute; its folder is the
  // output folder). Errors go to the Log. Returns success.
  static bool export_map(EditorSession& session, const std::string& object, const std::string& layer,
                         const std::string& what, const std::filesystem::path& file);
  // ddm.color of the layer: its own colour, or nullopt for the object's again.
  void set_layer_color(ToolContext& ctx, std::optional<glm::vec3> color);
  // Where the last draw_panel put the Fill and Bake buttons (ImGui screen coordinates: min x, min y, max x, max y).
  glm::vec4 fill_button() const { return fill_rect_; }
  glm::vec4 bake_button() const { return bake_rect_; }
  glm::vec4 remove_button() const { return remove_rect_; }

 private:
  const core::SceneObject* target(const ToolContext& ctx) const;
  // target(), and with `existing_layer` only when the chosen layer is on it; else null, after `refusal` went to the
  // Log panel as an error.
  const core::SceneObject* target_or_refuse(ToolContext& ctx, bool existing_layer, const std::string& refusal) const;
  void follow_selection(const ToolContext& ctx);
  void commit(ToolContext& ctx);
  void draw_layer_combo(ToolContext& ctx, const core::SceneObject* o);
  void draw_new_layer_fields(ToolContext& ctx, const core::SceneObject* o);
  void draw_size_field(ToolContext& ctx, const core::SceneObject* o, const char* name, double* value, double diag,
                       std::map<std::string, double>& typed, ui::SizeFieldState& state);
  void draw_layer_color(ToolContext& ctx, const core::SceneObject& o, const core::DdmLayer& layer);
  void apply_object_defaults(const core::SceneObject* o);  // base and tile size for a newly chosen object
  void draw_estimate(const core::SceneObject* o);          // what Fill would make (ddm_fill_estimate), cached
  void draw_fill_prompt(ToolContext& ctx);                 // "Fill anyway?" above the vertex budget
  void draw_map_export(ToolContext& ctx);  // Export: Position map... / Normal map... (ddm_paint_export.cpp)

  DdmPaintToolParams params_;
  std::string object_;
  std::string followed_selection_;  // selection the Object combo last followed
  std::string file_tile_;           // the path typed for a file tile
  std::string defaults_for_;        // the object whose defaults the panel holds ("\x01given": set_params' own)
  glm::ivec2 counts_{4, 4};         // the Counts field's value while tiles are laid by size
  double tile_size_ = 0.0;          // the Tile size field's value while tiles are laid by counts (0: none yet)
  // Sizes the user typed, per object: kept when the object is chosen again; others follow the object's size.
  std::map<std::string, double> typed_tile_size_, typed_height_;
  ui::SizeFieldState tile_size_state_, height_state_;  // as typed, and why limited
  std::string estimate_key_;                           // object, mesh and fill line the estimate below is for
  core::DdmFillEstimate estimate_;
  std::string estimate_error_;  // why there is no estimate (the error Fill would report)
  std::size_t ask_budget_ = 0;  // the budget the open "Fill anyway?" prompt was asked against (0: none open)

  std::optional<glm::dvec2> hover_;
  StrokeGesture gesture_;  // the drag under way, in the view at mouse-down
  bool erasing_ = false;   // the drag under way erases
  glm::vec4 fill_rect_{0.0f}, bake_rect_{0.0f}, remove_rect_{0.0f};
  glm::vec3 layer_color_{0.8f};  // the Layer colour swatch's value while it is edited
  bool color_editing_ = false;
  ui::DdmAnimParams anim_params_;  // the Animation section (ui/ddm_anim_panel.h)
  std::string anim_layer_;
};

}  // namespace trispline::editor
