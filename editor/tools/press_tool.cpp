#include "editor/tools/press_tool.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <iterator>

#include "core/commands/lattice_press.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/theme.h"

namespace trispline::editor {

namespace {
// The radius's declared default (lattice.press's object_size), a fraction of the object's bounding-box diagonal.
double default_radius_fraction() {
  return core::LatticePressCommand::schema().find("radius")->object_size->default_fraction;
}
constexpr double kDefaultStrengthFraction = 0.25;  // of the radius: like a Blender brush, relative to its size
constexpr double kMinSpacingFraction = 0.25;       // path samples closer than radius/4 to the previous one are dropped

// Tooltip of each falloff in core::kFalloffNames order: which are the seed's (§2.4.1, Fig. 2.7) and which Blender's.
constexpr const char* kFalloffTips[] = {
    "Seed's Gaussian: exp(-t^2 / (2 sigma^2)), sigma = 1/3",
    "Seed's hat = Blender's Linear: 1 - t",
    "Seed's box = Blender's Constant: 1 inside the sphere",
    "Blender's Smooth: 3s^2 - 2s^3, s = 1 - t",
    "Blender's Sphere: sqrt(1 - t^2)",
    "Blender's Root: sqrt(1 - t)",
    "Blender's Sharp: (1 - t)^2",
    "Blender's Constant: 1 inside the sphere",
};
static_assert(std::size(kFalloffTips) == core::kFalloffNames.size());

}  // namespace

nlohmann::json lattice_press_line(const core::LatticePressParams& params) {
  return core::LatticePressCommand::schema().to_json(params);
}

ui::ToolEntry PressTool::entry() const {
  return {"Press", "E", "Drag the sphere over a deformed object to press its lattice (Ctrl: pull)"};
}

void PressTool::activate(ToolContext& ctx) {
  if (!ctx.selected.empty()) follow_object(followed_selection_ = ctx.selected);
}

void PressTool::deactivate(ToolContext&) {
  hover_.reset();
  path_.clear();
  pressing_ = false;
  preview_.reset();
  caster_.reset();
  caster_mesh_.reset();
  if (pending_.valid()) pending_.wait();
  pending_ = {};
  pending_mesh_.reset();
}

void PressTool::mouse_away() {
  if (!pressing_) hover_.reset();
}

const core::SceneObject* PressTool::target(const ToolContext& ctx) const {
  const core::SceneObject* o = ctx.session.scene().find(object_);
  return o && o->ffd && o->world_mesh ? o : nullptr;
}

double PressTool::diagonal(const core::SceneObject& o) const {
  if (!o.world_mesh) return 0.0;
  if (diagonal_mesh_.lock() != o.world_mesh) {
    diagonal_ = core::mesh_bounds(*o.world_mesh).diagonal();
    diagonal_mesh_ = o.world_mesh;
  }
  return diagonal_;
}

double PressTool::radius(const ToolContext& ctx) const {
  if (params_.radius > 0.0) return params_.radius;
  const core::SceneObject* o = target(ctx);
  return o ? default_radius_fraction() * diagonal(*o) : 0.0;
}

double PressTool::strength(const ToolContext& ctx) const {
  return params_.strength > 0.0 ? params_.strength : kDefaultStrengthFraction * radius(ctx);
}

namespace {
std::unique_ptr<core::RayCaster> build_caster(std::shared_ptr<const core::TriMesh> mesh) {
  auto caster = std::make_unique<core::RayCaster>(core::BuildQuality::interactive);  // rebuilt after every press
  caster->add_mesh(*mesh);
  caster->commit();
  return caster;
}
}  // namespace

std::optional<glm::dvec3> PressTool::cast(const ToolContext& ctx, glm::dvec2 px, bool need_current) {
  const core::SceneObject* o = target(ctx);
  if (!o || !o->visible || o->world_mesh->empty()) return std::nullopt;
  if (caster_mesh_ != o->world_mesh) {
    // The mesh changed (a press, undo): build the new BVH on a worker thread and keep hovering over the previous
    // one meanwhile (a 1 M-vertex mesh takes most of a second); a drag waits for the current one.
    if (!pending_.valid() || pending_mesh_ != o->world_mesh) {
      pending_mesh_ = o->world_mesh;
      pending_ = std::async(std::launch::async, build_caster, pending_mesh_);
    }
    const bool ready = pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    if (ready || !caster_ || need_current) {
      caster_ = pending_.get();
      caster_mesh_ = std::move(pending_mesh_);
      pending_mesh_.reset();
    }
  }
  const auto hit = caster_->intersect(ctx.view.eye, ctx.view.ray_direction(px));
  if (!hit) return std::nullopt;
  return hit->position;
}

void PressTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  try {
    hover_ = cast(ctx, in.mouse_px, in.left_pressed || pressing_);
  } catch (const std::exception& e) {  // non-finite mesh positions
    hover_.reset();
    ctx.session.messages().error(std::string("press: ray casting failed: ") + e.what());
    return;
  }
  hover_radius_ = radius(ctx);
  if (in.left_pressed) {
    preview_strength_ = -1.0;
    pressing_ = true;
    pull_ = in.ctrl;
    path_.clear();
  }
  if (pressing_ && in.left_down && hover_) {
    if (path_.empty() || glm::length(*hover_ - path_.back()) >= kMinSpacingFraction * hover_radius_)
      path_.push_back(*hover_);
  }
  if (pressing_ && (in.left_released || !in.left_down)) {
    pressing_ = false;
    commit(ctx);
  }
}

std::optional<Tool::LivePreview> PressTool::live_preview(const ToolContext& ctx) {
  const core::SceneObject* o = target(ctx);
  if (!o) {
    preview_.reset();
    return std::nullopt;
  }
  if (pressing_ && !path_.empty()) {
    if (!preview_ || preview_base_ != o->ffd || preview_samples_ != path_.size()) {
      try {
        if (params_.keep_fold_free) {
          try {
            core::FoldFreePress press =
                core::press_lattice_fold_free(o->ffd->lattice, path_, hover_radius_, signed_strength(ctx), falloff());
            preview_strength_ = press.limited ? std::abs(press.strength) : -1.0;
            preview_ = std::make_shared<const core::TrivariateBSpline<glm::dvec3>>(std::move(press.lattice));
          } catch (const std::invalid_argument& e) {  // not certified, or cannot move: the command will refuse
            preview_strength_ = std::nan("");
            preview_refusal_ = e.what();
            preview_.reset();
          }
        } else {
          preview_ = std::make_shared<const core::TrivariateBSpline<glm::dvec3>>(
              core::press_lattice(o->ffd->lattice, path_, hover_radius_, signed_strength(ctx), falloff()));
        }
        preview_base_ = o->ffd;
        preview_samples_ = path_.size();
      } catch (const std::exception&) {  // a degenerate column: the command at mouse-up reports it
        preview_.reset();
      }
    }
  } else if (preview_ && (preview_base_ != o->ffd || --preview_linger_ < 0)) {
    preview_.reset();  // the command replaced the lattice (or failed): show the object's own
  }
  if (!preview_) return std::nullopt;
  return LivePreview{object_, preview_};
}

void PressTool::commit(ToolContext& ctx) {
  std::vector<glm::dvec3> path = std::move(path_);
  path_.clear();
  preview_linger_ = 3;
  if (path.empty()) return;  // the drag never touched the object
  const core::SceneObject* o = target(ctx);
  if (!o) {
    ctx.session.messages().error("lattice.press: choose an object with an FFD lattice in the Tool panel first");
    return;
  }
  core::LatticePressParams p = params_;
  p.object = object_;
  p.path = std::move(path);
  p.radius = radius(ctx);
  p.strength = signed_strength(ctx);
  const nlohmann::json line = lattice_press_line(p);
  ctx.execute_deferred((pull_ ? "Pulling " : "Pressing ") + object_, line);
}

void PressTool::follow_object(const std::string& name) {
  if (name == object_) return;
  if (!object_.empty()) typed_[object_] = {params_.radius, params_.strength};  // for when that object comes back
  object_ = name;
  const auto it = typed_.find(name);
  params_.radius = it != typed_.end() ? it->second.first : 0.0;  // unset: from the object's size
  params_.strength = it != typed_.end() ? it->second.second : 0.0;
  radius_state_.limit.clear(), strength_state_.limit.clear();
}

std::string PressTool::hint() const {
  if (pressing_)
    return pull_ ? "Release to pull the lattice" : "Release to press the lattice (Ctrl at mouse-down pulls)";
  if (object_.empty()) return "Choose an object with an FFD lattice in the Tool panel";
  return "Drag over " + object_ + " to press its lattice; Ctrl-drag pulls";
}

// The Object combo; the object to press (null when none is chosen or it no longer exists).
const core::SceneObject* PressTool::draw_object_combo(ToolContext& ctx) {
  // The combo follows the selection until the user picks another object there.
  if (!ctx.selected.empty() && ctx.selected != followed_selection_) follow_object(followed_selection_ = ctx.selected);
  const core::Scene& scene = ctx.session.scene();
  if (ImGui::BeginCombo("Object", object_.empty() ? "(none)" : object_.c_str())) {
    for (const core::SceneObject& o : scene.objects()) {
      const std::string label = o.ffd ? o.name : o.name + "  (no lattice)";
      if (ImGui::Selectable(label.c_str(), o.name == object_)) follow_object(o.name);
    }
    ImGui::EndCombo();
  }
  const core::SceneObject* o = scene.find(object_);
  if (o && !o->ffd)
    ImGui::TextColored(ui::colors::dim, "%s has no FFD lattice: bind one first (e.g. lattice.ring).", object_.c_str());
  return o;
}

// Radius: drag, or one click and type. A value outside what the object takes is limited, and the field says so
// (amber, the reason in its tooltip) and the Log once. Returns the radius shown, world units.
double PressTool::draw_radius_field(ToolContext& ctx, const core::SceneObject* o, double diag) {
  double r = radius(ctx);
  if (r <= 0.0) r = diag > 0.0 ? default_radius_fraction() * diag : 0.1;
  const bool typed = params_.radius > 0.0 && o;  // a Default button follows the field: it narrows to leave room
  if (typed) {
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - ImGui::CalcTextSize("Default").x - 2.0f * style.FramePadding.x -
                            style.ItemSpacing.x);
  }
  const std::string limited = ui::size_param_widget(core::LatticePressCommand::schema(), "radius", params_, diag, r,
                                                    radius_state_, "press.radius");
  if (!limited.empty())
    ctx.session.messages().warning("Press radius " + ui::short_number(radius_state_.typed) + ": " + limited);
  if (typed) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Default")) params_.radius = 0.0, radius_state_.limit.clear();
  }
  return r;
}

// Strength, limited as the radius is; `r` the radius shown. Returns the strength shown, world units.
double PressTool::draw_strength_field(ToolContext& ctx, double diag, double r) {
  const std::string limited = ui::size_param_widget(core::LatticePressCommand::schema(), "strength", params_, diag,
                                                    kDefaultStrengthFraction * r, strength_state_, "press.strength");
  if (!limited.empty())
    ctx.session.messages().warning("Press strength " + ui::short_number(strength_state_.typed) + ": " + limited);
  return params_.strength > 0.0 ? params_.strength : kDefaultStrengthFraction * r;
}

void PressTool::draw_falloff_combo() {
  const core::Falloff chosen = falloff();
  const std::string current(core::to_string(chosen));
  if (ImGui::BeginCombo("Falloff", current.c_str())) {
    for (std::size_t i = 0; i < core::kFalloffNames.size(); ++i) {
      const std::string name(core::kFalloffNames[i]);
      if (ImGui::Selectable(name.c_str(), i == std::size_t(chosen))) params_.falloff = name;
      ui::probe::item("press.falloff." + name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kFalloffTips[i]);
    }
    ImGui::EndCombo();
  }
  ui::probe::item("press.falloff");
  ui::probe::value("press.falloff", current);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kFalloffTips[std::size_t(chosen)]);
}

// Keep fold-free, and during a drag what it does to the press; `s` the strength shown.
void PressTool::draw_fold_free(double s) {
  ImGui::Checkbox("Keep fold-free", &params_.keep_fold_free);
  ui::probe::item("press.keep_fold_free");
  ui::probe::value("press.keep_fold_free", params_.keep_fold_free ? "1" : "0");
  ui::probe::value("press.strength", std::to_string(s));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Limit each press's strength (bisection) so that the lattice stays certified fold-free:\n"
        "det J > 0 everywhere, proven by its Bernstein coefficients (View > Fold certificate shows it).\n"
        "A lattice that is not certified before the press is refused.");
  if (params_.keep_fold_free && pressing_) {
    if (std::isnan(preview_strength_)) {
      ImGui::PushStyleColor(ImGuiCol_Text, ui::colors::warning);
      ImGui::TextWrapped("The press will be refused: %s", preview_refusal_.c_str());
      ImGui::PopStyleColor();
      ui::probe::value("press.refusal", preview_refusal_);
    } else if (preview_strength_ >= 0.0)
      ImGui::TextColored(ui::colors::dim, "Limited to strength %.4g to stay fold-free", preview_strength_);
  }
}

void PressTool::draw_panel(ToolContext& ctx) {
  const core::SceneObject* o = draw_object_combo(ctx);
  // Before an object is chosen the sizes follow the scene's, so the fields never start at a meaningless 0.001.
  const core::Aabb scene_box = ctx.session.scene().bounds();
  const double diag = o ? diagonal(*o) : scene_box.valid() ? scene_box.diagonal() : 0.0;
  const double r = draw_radius_field(ctx, o, diag);
  const double s = draw_strength_field(ctx, diag, r);
  draw_falloff_combo();
  draw_fold_free(s);

  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextWrapped(
      "Left-drag over the object: control points inside the swept sphere move into the volume along their "
      "columns (one undoable step per drag). Ctrl-drag pulls them out. Set the radius here (F frames the "
      "selection).");
}

void PressTool::decorate(gpu::ViewOptions& options) const {
  if (hover_ && hover_radius_ > 0.0) {
    gpu::SphereOverlay sphere;
    sphere.centre = *hover_;
    sphere.radius = hover_radius_;
    if (pressing_ && pull_) sphere.color = {1.0f, 0.55f, 0.3f, 0.30f};  // pulling: warm tint
    options.overlays.spheres.push_back(sphere);
  }
  // The sphere centres sampled along the drag.
  if (!path_.empty())
    options.overlays.points.push_back({path_, {1.0f, 0.85f, 0.3f, 1.0f}, options.style.contact_point_px});
}

}  // namespace trispline::editor
