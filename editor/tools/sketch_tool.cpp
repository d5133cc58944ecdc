#include "editor/tools/sketch_tool.h"

#include "core/commands/camera_set.h"
#include "editor/session.h"
#include "ui/theme.h"

#include <imgui.h>

namespace trispline::editor {

namespace {
constexpr double kMinPointSpacingPx = 2.0;  // stroke points closer than this to the previous one are dropped

nlohmann::json vec3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

nlohmann::json place_sketch_line(const std::string& object, const std::vector<glm::dvec2>& stroke_px,
                                 const ui::PlacementParams& p, const core::Camera& view,
                                 const std::vector<std::string>& ignore) {
  nlohmann::json stroke = nlohmann::json::array();
  for (const glm::dvec2& q : stroke_px) stroke.push_back({q.x, q.y});
  nlohmann::json line = {{"cmd", "place.sketch"},
          {"object", object},
          {"stroke", stroke},
          {"width", p.width},
          {"height", p.height},
          {"samples", {p.samples[0], p.samples[1]}},
          {"volume", p.offset_volume ? "offset" : "extrude"},
          {"order", {p.order[0], p.order[1], p.order[2]}},
          {"controls", {p.controls[0], p.controls[1], p.controls[2]}},
          {"length_axis", ui::axis_name(p.length_axis)},
          {"up_axis", ui::axis_name(p.up_axis)},
          {"camera",
           {{"eye", vec3(view.eye)},
            {"target", vec3(view.target)},
            {"up", vec3(view.up)},
            {"fov_deg", view.fov_deg},
            {"viewport", {view.viewport.x, view.viewport.y}}}}};
  if (!ignore.empty()) line["ignore"] = ignore;
  ui::add_placement_extras(p, line);  // profiles d(u), h(u), springs, extent (only when not off)
  return line;
}

bool parse_place_sketch_line(const nlohmann::json& j, std::string* object, std::vector<glm::dvec2>* stroke,
                             ui::PlacementParams* p, std::optional<core::Camera>* camera,
                             std::vector<std::string>* ignore) {
  try {
    auto axis = [](const std::string& a) { return a == "x" ? 0 : a == "y" ? 1 : 2; };
    *object = j.at("object").get<std::string>();
    stroke->clear();
    for (const auto& q : j.at("stroke")) stroke->push_back({q.at(0).get<double>(), q.at(1).get<double>()});
    p->width = j.at("width").get<double>();
    p->height = j.at("height").get<double>();
    p->offset_volume = j.value("volume", "extrude") == "offset";
    for (int a = 0; a < 2 && j.contains("samples"); ++a) p->samples[a] = j["samples"].at(a).get<int>();
    for (int a = 0; a < 3 && j.contains("order"); ++a) p->order[a] = j["order"].at(a).get<int>();
    for (int a = 0; a < 3 && j.contains("controls"); ++a) p->controls[a] = j["controls"].at(a).get<int>();
    p->length_axis = axis(j.value("length_axis", "x"));
    p->up_axis = axis(j.value("up_axis", "y"));
    ui::read_placement_extras(j, *p);
    camera->reset();
    if (j.contains("camera")) *camera = core::CameraSetCommand::parse_camera(j["camera"]);
    if (ignore) *ignore = j.value("ignore", std::vector<std::string>{});
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

ui::ToolEntry SketchTool::entry() const {
  return {"Sketch placement", "W", "Drag a stroke over the scene to place the chosen object along it"};
}

void SketchTool::activate(ToolContext& ctx) {
  if (!ctx.selected.empty()) object_ = followed_selection_ = ctx.selected;
}

void SketchTool::deactivate(ToolContext&) {
  stroke_.clear();
  drawing_ = false;
}

std::string SketchTool::hint() const {
  if (drawing_) return "Release to place";
  return object_.empty() ? "Choose the object to place in the Tool panel" : "Drag to sketch a stroke for " + object_;
}

void SketchTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  if (in.left_pressed) {
    stroke_ = {in.mouse_px};
    stroke_view_ = ctx.view;  // pixels of this view, whatever the camera does until mouse-up
    drawing_ = true;
  }
  if (drawing_ && in.left_down) {
    if (glm::length(in.mouse_px - stroke_.back()) >= kMinPointSpacingPx) stroke_.push_back(in.mouse_px);
  }
  if (drawing_ && (in.left_released || !in.left_down)) {
    drawing_ = false;
    std::vector<glm::dvec2> stroke = std::move(stroke_);
    stroke_.clear();
    if (stroke.size() < 2) return;  // a click, not a stroke
    if (object_.empty() || !ctx.session.scene().find(object_)) {
      ctx.session.messages().error("place.sketch: choose the object to place in the Tool panel first");
      return;
    }
    // The rays pass through what the viewport hides, as picking does.
    std::vector<std::string> ignore;
    for (const std::string& name : ctx.hidden)
      if (name != object_ && ctx.session.scene().find(name)) ignore.push_back(name);
    place(ctx, std::move(stroke), stroke_view_, std::move(ignore));
  }
}

void SketchTool::place(ToolContext& ctx, std::vector<glm::dvec2> stroke, const core::Camera& view,
                       std::vector<std::string> ignore) {
  const nlohmann::json line = place_sketch_line(object_, stroke, params_, view, ignore);
  const std::string object = object_;
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
  const nlohmann::json line = place_sketch_line(last_object_, last_stroke_, params_, last_view_, last_ignore_);
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

void SketchTool::set_params(const ui::PlacementParams& params, ToolContext& ctx) {
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
  std::optional<core::Camera> camera;
  ui::PlacementParams params;
  if (!parse_place_sketch_line(top.to_json(), &last_object_, &last_stroke_, &params, &camera, &last_ignore_)) return;
  params_ = params;
  last_view_ = camera ? *camera : ctx.session.scene().camera;  // a camera-less line used the scene camera
  last_applied_ = h.applied();
  last_command_ = &top;
}

void SketchTool::draw_panel(ToolContext& ctx) {
  adopt_top(ctx);
  // The combo follows the selection until the user picks another object there.
  if (!ctx.selected.empty() && ctx.selected != followed_selection_) object_ = followed_selection_ = ctx.selected;
  std::vector<std::string> names;
  for (const core::SceneObject& o : ctx.session.scene().objects()) names.push_back(o.name);

  const ui::PlacementPanelResult r = ui::draw_placement_panel(params_, object_, names);
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
  if (drawing_) options.stroke_px = stroke_;
}

}  // namespace trispline::editor
