#include "editor/tools/sketch_tool.h"

#include <imgui.h>

#include <cmath>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "ui/gui_probe.h"
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
    last_step_.mark(h);
  });
}

bool SketchTool::last_is_top(const History& h) const {
  return last_step_.is_top(h, "place.sketch", last_object_, last_stroke_.size());
}

void SketchTool::replace_last(ToolContext& ctx) {
  if (!last_is_top(ctx.session.history())) {  // nothing of ours to re-run: the new values apply to the next stroke
    if (!last_object_.empty())
      ctx.session.messages().info("Sketch values apply to the next stroke: the placement of '" + last_object_ +
                                  "' is not the latest step (undo what came after it to edit it)");
    return;
  }
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
    last_step_.mark(h);
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
  typed_sizes_[p.object] = {p.width, p.height};  // the sizes that placement used belong to its object
  last_object_ = p.object;
  last_stroke_ = p.stroke;
  last_ignore_ = p.ignore;
  last_view_ = p.camera ? *p.camera : ctx.session.scene().camera;  // a camera-less line used the scene camera
  const std::string object = params_.object;                       // the combo keeps the user's choice
  params_ = p;
  params_.object = object;
  panel_ = ui::PlacementPanelState::from(p);
  last_step_.mark(h);
}

void SketchTool::apply_object_sizes(const ToolContext& ctx) {
  if (params_.object == sized_for_) return;
  sized_for_ = params_.object;
  if (const auto it = typed_sizes_.find(params_.object); it != typed_sizes_.end()) {
    params_.width = it->second.first, params_.height = it->second.second;
    return;
  }
  const core::SceneObject* o = ctx.session.scene().find(params_.object);
  if (!o || !o->rest_mesh || o->rest_mesh->empty()) return;
  const core::Aabb box = core::mesh_bounds(o->world_rest_mesh());
  const glm::dvec3 extent = box.hi - box.lo;
  auto axis = [](const std::string& a) { return a == "x" ? 0 : a == "y" ? 1 : 2; };
  const int length = axis(params_.length_axis), up = axis(params_.up_axis);
  if (length == up) return;
  const int across = 3 - length - up;
  if (extent[across] > 0.0 && extent[up] > 0.0 && std::isfinite(extent[across]) && std::isfinite(extent[up]))
    params_.width = 0.5 * extent[across], params_.height = extent[up];
}

void SketchTool::draw_panel(ToolContext& ctx) {
  adopt_top(ctx);
  // The combo follows the selection until the user picks another object there.
  if (!ctx.selected.empty() && ctx.selected != followed_selection_) params_.object = followed_selection_ = ctx.selected;
  std::vector<std::string> names;
  for (const core::SceneObject& o : ctx.session.scene().objects()) names.push_back(o.name);

  apply_object_sizes(ctx);
  ui::probe::value("sketch.width", std::to_string(params_.width));
  ui::probe::value("sketch.height", std::to_string(params_.height));
  const double width_before = params_.width, height_before = params_.height;
  const ui::PlacementPanelResult r = ui::draw_placement_panel(params_, panel_, names);
  if (r.reset) {
    typed_sizes_.erase(params_.object);
    sized_for_.clear();
    apply_object_sizes(ctx);
  } else if (params_.width != width_before || params_.height != height_before) {
    // With no object chosen the values edit the adopted placement: they are its object's.
    typed_sizes_[params_.object.empty() ? last_object_ : params_.object] = {params_.width, params_.height};
  }
  if (r.object_changed) apply_object_sizes(ctx);
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
