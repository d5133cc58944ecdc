// trispline::editor::IncisionTool — the incision drawing tool (seed §6.4, Eq. 6.2, Fig. 6.5, 6.6, 6.8),
// Blender's Knife key K. Left-drag over an object (the one under the cursor at mouse-down, else the selected
// one, else the first object the stroke passes over) collects the stroke in viewport pixels (top-left origin) of the
// view at mouse-down. While dragging, at most every preview_interval_ms, the cut is previewed on the UI thread:
// core::fit_incision_frame + core::incise on the object's world_mesh with the panel's parameters; the view shows the
// generator curve G(v), the cut lattice and the cut mesh in place of the object (a curve, a lattice and a mesh in
// gpu::Overlays), or only the stroke while it does not lie on the surface. On
// mouse-up the tool executes ONE `incision.draw` command (docs/commands.md) carrying the view at mouse-down
// ("camera"), so the stroke's pixels replay in that view.
// A click without a drag issues nothing; errors go to the Log panel and leave the scene as it was.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/commands/incision_draw.h"
#include "core/incision/incision.h"
#include "core/raycast/ray_caster.h"
#include "editor/commands/history.h"
#include "editor/tools/last_step.h"
#include "editor/tools/stroke_gesture.h"
#include "editor/tools/tool.h"
#include "ui/key_pair_panel.h"
#include "ui/param_widgets.h"

namespace trispline::editor {

// The tool's parameters are incision.draw's own (core::IncisionParams, declared in core/commands/incision_draw.cpp),
// with the tool's convention that a width or depth ≤ 0 and an opening < 0 mean "relative to the object" (resolved()).
core::IncisionParams incision_tool_defaults();

// The incision.draw line: {"cmd":"incision.draw","object":ID,"stroke":[[px,py],...] (#S × 2 viewport pixels),
// "width":a,"depth":b,"opening":c,"walls":bool,"order":o,"kernel":k} (parameters resolved: width, depth > 0), plus
// "camera" (as place.sketch's: the view the pixels belong to) when `view` is given.
nlohmann::json incision_draw_line(const std::string& object, const std::vector<glm::dvec2>& stroke_px,
                                  const core::IncisionParams& params,
                                  const std::optional<core::Camera>& view = std::nullopt);

class IncisionTool : public Tool {
 public:
  ui::ToolEntry entry() const override;
  void activate(ToolContext& ctx) override;
  void deactivate(ToolContext& ctx) override;
  void handle_input(const ToolInput& in, ToolContext& ctx) override;
  void mouse_away() override {}
  void draw_panel(ToolContext& ctx) override;
  void decorate(gpu::ViewOptions& options) const override;
  std::string hint() const override;
  bool owns_mouse() const override { return gesture_.drawing(); }

  const core::IncisionParams& params() const { return params_; }
  void set_params(const core::IncisionParams& p) { params_ = p; }
  // The parameters with the sizes typed in the panel for `object` (each object keeps its own), and unset width /
  // depth / opening replaced by their declared object_size defaults (incision_schema: 0.02 / 0.02 / 0.006 × the
  // bounding-box diagonal of `object`'s world_mesh; unchanged when it has none).
  core::IncisionParams resolved(const core::SceneObject* object) const;
  // Whether the last cut this tool made is the newest step of the history: a size edited in the panel then re-runs
  // it (undo + incision.draw with the new sizes, one undoable step); otherwise the Log says the sizes apply to the
  // next cut.
  bool can_rerun(const ToolContext& ctx) const { return last_is_top(ctx.session.history()); }
  // Re-runs the last cut with the panel's sizes (see can_rerun); false, with the reason in the Log, when it cannot.
  bool rerun_last(ToolContext& ctx);
  // Minimum time between two previews while dragging (0: after every new stroke point; tests use 0).
  void set_preview_interval_ms(double ms) { preview_interval_ms_ = ms; }

  // The preview of the drag under way (empty when not dragging or when the stroke misses the surface).
  const std::string& target() const { return target_; }                        // object being cut
  const std::vector<glm::dvec2>& stroke() const { return gesture_.points(); }  // pixels so far
  const std::vector<glm::dvec3>& preview_curve() const { return curve_; }      // G(v) sampled, world units
  const std::shared_ptr<const core::TriMesh>& preview_mesh() const { return preview_mesh_; }  // the cut surface
  // The preview's opened cut lattice (seed Eq. 6.2, C⁻¹ at u = 1/2), world units; null without a preview.
  const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>& preview_lattice() const { return preview_lattice_; }
  const std::string& preview_error() const { return preview_error_; }  // why the last preview showed no cut

 private:
  const core::SceneObject* object(const ToolContext& ctx) const;
  std::optional<std::string> pick(const ToolContext& ctx, glm::dvec2 px) const;  // object under pixel px
  const core::RayCaster* caster_for(const core::SceneObject& o);                 // cached per world_mesh
  void update_preview(const ToolContext& ctx);
  void commit(ToolContext& ctx);
  void clear_preview();
  bool last_is_top(const History& h) const;

  // Sizes typed in the panel for one object: width, depth and opening of an IncisionParams drawn by
  // ui::size_param_widget (≤ 0: not typed, relative to the object; an opening typed as 0 is kept as 1e-12).
  using TypedSizes = core::IncisionParams;
  std::map<std::string, TypedSizes> typed_;
  ui::SizeFieldState width_state_, depth_state_, opening_state_;  // as typed, and why limited
  // The last cut this tool made (for re-running it when a size is edited).
  std::string last_object_;
  std::vector<glm::dvec2> last_stroke_;
  core::Camera last_view_;
  TypedSizes last_typed_;  // the sizes typed for last_object_ when that cut was made
  LastStep last_step_;

  core::IncisionParams params_ = incision_tool_defaults();
  ui::KeyPairParams opening_keys_{1, -1, 0.0, 1.0, "smooth"};  // frame_to < 0: the timeline's end when first shown
  StrokeGesture gesture_;
  std::string target_;

  std::vector<glm::dvec3> curve_;
  std::shared_ptr<const core::TriMesh> preview_mesh_;
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> preview_lattice_;
  std::string preview_error_;
  std::size_t previewed_points_ = 0;
  std::chrono::steady_clock::time_point last_preview_{};
  double preview_interval_ms_ = 50.0;

  std::shared_ptr<const core::TriMesh> caster_mesh_;  // held so the pointer cannot be reused by another mesh
  std::unique_ptr<core::RayCaster> caster_;
};

}  // namespace trispline::editor
