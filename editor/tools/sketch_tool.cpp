#include "editor/tools/sketch_tool.h"

#include <imgui.h>

#include "editor/session.h"
#include "ui/theme.h"

namespace trispline::editor {

nlohmann::json place_sketch_line(core::PlaceSketchParams params, const std::vector<glm::dvec2>& stroke_px,
                                 const core::Camera& view, const std::vector<std::string>& ignore) {
  params.stroke = stroke_px;
  params.camera = view;
  params.ignore = ignore;
  return core::PlaceSketchCommand::schema().to_json(params);
}

ui::ToolEntry SketchTool::entry() const {
  return {"Sketch placement", "W", "Drag a stroke over the scene to place the chosen object along it"};
}

void SketchTool::activate(ToolContext& ctx) {
  if (!ctx.selected.empty()) params_.object = followed_selection_ = ctx.selected;
}

void SketchTool::deactivate(ToolContext&) { gesture_.cancel(); }

std::string SketchTool::hint() const {
  if (gesture_.drawing()) return "Release to place";
  return params_.object.empty() ? "Choose the object to place in the Tool panel"
                                : "Drag to sketch a stroke for " + params_.object;
}

void SketchTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  if (gesture_.update(in, ctx.view) == StrokeGesture::Event::Ended) {
    std::vector<glm::dvec2> stroke = gesture_.take();
    if (stroke.size() < 2) return;  // a click, not a stroke
    if (params_.object.empty() || !ctx.session.scene().find(params_.object)) {
      ctx.session.messages().error("place.sketch: choose the object to place in the Tool panel first");
      return;
    }
    // The rays pass through what the viewport hides (object.visibility), as picking does: place.sketch skips it.
    place(ctx, std::move(stroke), gesture_.view(), {});
  }
}

void SketchTool::place(ToolContext& ctx, std::vector<glm::dvec2> stroke, const core::Camera& view,
                       std::vector<std::string> ignore) {
  const nlohmann::json line = place_sketch_line(params_, stroke, view, ignore);
  const std::string object = params_.object;
  EditorSession& session = ctx.session;  // outlives the deferred work; ctx may not
  ctx.defer("Placing " + object + " along the stroke", [this, &session, line, stroke, view, object, ignore]() {
    if (!session.execute(line)) return;
    History& h = session.history();
    last_stroke_ = stroke;
    last_view_ = view;
    last_ignore_ = ignore;
    last_object_ = object;
    last_applied_ = h.applied();
    last_command_ = &h.at(h.applied() - 1);
  });
}

bool SketchTool::last_is_top(const History& h) const {
  if (!last_command_ || h.applied() != last_applied_ || h.applied() == 0) return false;
  const core::Command& top = h.at(h.applied() - 1);
  if (&top != last_command_ || top.id() != "place.sketch") return false;
  // The address alone could be a new command reusing freed memory: check the content too.
  const nlohmann::json j = top.to_json();
  return j.value("object", "") == last_object_ && j.contains("stroke") && j["stroke"].size() == last_stroke_.size();
}

void SketchTool::replace_last(ToolContext& ctx) {
  if (!last_is_top(ctx.session.history()))
    return;  // nothing of ours to re-run: the new values apply to the next stroke
  core::PlaceSketchParams p = params_;
  p.object = last_object_;
  const nlohmann::json line = place_sketch_line(p, last_stroke_, last_view_, last_ignore_);
  EditorSession& s = ctx.session;
  ctx.defer("Re-running the placement of " + last_object_, [this, &s, line]() {
    if (!last_is_top(s.history())) return;
    if (!s.undo()) return;
    if (!s.execute(line)) {
      s.redo();  // the edited placement failed: put the previous one back
      return;
    }
    History& h = s.history();
    last_applied_ = h.applied();
    last_command_ = &h.at(h.applied() - 1);
  });
}

bool SketchTool::can_rerun(const ToolContext& ctx) const { return last_is_top(ctx.session.history()); }

void SketchTool::set_params(const core::PlaceSketchParams& params, ToolContext& ctx) {
  params_ = params;
  if (params_.length_axis != params_.up_axis) replace_last(ctx);
}

void SketchTool::adopt_top(const ToolContext& ctx) {
  const History& h = ctx.session.history();
  if (h.applied() == 0 || last_is_top(h)) return;
  const core::Command& top = h.at(h.applied() - 1);
  if (&top == adopt_checked_) return;  // looked at it already
  adopt_checked_ = &top;
  if (top.id() != "place.sketch") return;
  const auto* placed = dynamic_cast<const core::PlaceSketchCommand*>(&top);
  if (!placed) return;
  const core::PlaceSketchParams& p = placed->params();
  last_object_ = p.object;
  last_stroke_ = p.stroke;
  last_ignore_ = p.ignore;
  last_view_ = p.camera ? *p.camera : ctx.session.scene().camera;  // a camera-less line used the scene camera
  const std::string object = params_.object;                       // the combo keeps the user's choice
  params_ = p;
  params_.object = object;
  panel_ = ui::PlacementPanelState::from(p);
  last_applied_ = h.applied();
  last_command_ = &top;
}

void SketchTool::draw_panel(ToolContext& ctx) {
  adopt_top(ctx);
  // The combo follows the selection until the user picks another object there.
  if (!ctx.selected.empty() && ctx.selected != followed_selection_) params_.object = followed_selection_ = ctx.selected;
  std::vector<std::string> names;
  for (const core::SceneObject& o : ctx.session.scene().objects()) names.push_back(o.name);

  const ui::PlacementPanelResult r = ui::draw_placement_panel(params_, panel_, names);
  if (r.committed) set_params(params_, ctx);

  ImGui::Spacing();
  ImGui::Separator();
  if (last_is_top(ctx.session.history())) {
    ImGui::TextColored(ui::colors::accent, "Editing the last placement of %s", last_object_.c_str());
    ImGui::TextWrapped("Parameter changes re-run it as one undoable step.");
  } else {
    ImGui::TextWrapped(
        "Left-drag over the scene to sketch a stroke; the object is deformed to lie along it on "
        "whatever the rays hit.");
  }
}

void SketchTool::decorate(gpu::ViewOptions& options) const {
  if (gesture_.drawing()) options.add_stroke(gesture_.points());
}

}  // namespace trispline::editor
