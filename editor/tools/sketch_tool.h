// trispline::editor::SketchTool — Sketch placement (seed §2.3.1): choose the object to place, left-drag a stroke
// over the scene; on mouse-up the tool executes one `place.sketch` command (docs/commands.md) carrying the
// stroke (viewport pixels, top-left origin), the parameters, the view at mouse-down ("camera"; the editor does not
// move the camera while a stroke is drawn), so the log line is self-contained; objects hidden in the viewport
// (object.visibility, in the log) let the rays pass, as picking does.
//
// Changing a parameter after a placement re-runs it as ONE undoable step: when the tool's last place.sketch is
// still the top applied command, it is undone and the edited command executed in its place (if that fails the
// old placement is redone, so the scene is as before). Edits commit on IsItemDeactivatedAfterEdit, never per frame.
// A place.sketch on top of the history that came from elsewhere (an opened log, a redo) is adopted the same way,
// like Blender's "Adjust Last Operation" panel: its parameters fill the panel and edits re-run it.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "editor/commands/history.h"
#include "editor/tools/last_step.h"
#include "editor/tools/stroke_gesture.h"
#include "editor/tools/tool.h"
#include "ui/placement_panel.h"

namespace trispline::editor {

// The place.sketch line of `params` with the stroke drawn in `view` (its "camera") and `ignore` (omitted when empty).
nlohmann::json place_sketch_line(core::PlaceSketchParams params, const std::vector<glm::dvec2>& stroke_px,
                                 const core::Camera& view, const std::vector<std::string>& ignore = {});

class SketchTool : public Tool {
 public:
  ui::ToolEntry entry() const override;
  void activate(ToolContext& ctx) override;
  void deactivate(ToolContext& ctx) override;
  void handle_input(const ToolInput& in, ToolContext& ctx) override;
  void draw_panel(ToolContext& ctx) override;
  void decorate(gpu::ViewOptions& options) const override;
  std::string hint() const override;
  bool owns_mouse() const override { return gesture_.drawing(); }

  const core::PlaceSketchParams& params() const { return params_; }
  // What a committed edit in the panel does: takes `params`, and re-runs the tool's last placement with them as
  // one undoable step when it is still the top of the history (otherwise they apply to the next stroke).
  void set_params(const core::PlaceSketchParams& params, ToolContext& ctx);
  void set_object(const std::string& name) { params_.object = name; }
  // True while the last placement (the tool's own or an adopted one) can be re-run by a parameter change.
  bool can_rerun(const ToolContext& ctx) const;

 private:
  void place(ToolContext& ctx, std::vector<glm::dvec2> stroke, const core::Camera& view,
             std::vector<std::string> ignore);
  void replace_last(ToolContext& ctx);  // parameter change after a placement
  bool last_is_top(const History& history) const;
  void adopt_top(const ToolContext& ctx);  // a place.sketch from elsewhere on top of the history
  // When the object to place changes: its own typed (or adopted) width and height, else sizes from its rest bounds
  // (half-width: half its extent across the stroke; height: its extent along up_axis), so it keeps its size.
  void apply_object_sizes(const ToolContext& ctx);

  core::PlaceSketchParams params_;  // the next placement's parameters; object = the object to place
  ui::PlacementPanelState panel_;
  std::string followed_selection_;                                // selection the combo last followed
  std::map<std::string, std::pair<double, double>> typed_sizes_;  // per object: width, height typed or adopted
  std::string sized_for_;                                         // the object whose sizes params_ holds
  StrokeGesture gesture_;

  // The tool's last successful placement (for re-running with new parameters).
  std::vector<glm::dvec2> last_stroke_;
  core::Camera last_view_;
  std::vector<std::string> last_ignore_;
  std::string last_object_;
  LastStep last_step_;
  const void* adopt_checked_ = nullptr;  // top command adopt_top() examined last
};

}  // namespace trispline::editor
