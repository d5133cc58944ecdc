#include "editor/tools/incision_tool.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "core/commands/incision_animate.h"
#include "editor/commands/command_registry.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/keyed_weight_section.h"
#include "editor/tools/select_tool.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::editor {

namespace {
constexpr int kCurveSamples = 64;  // G(v) samples shown while dragging

// The declared default of a size field of incision.draw, a fraction of the object's bounding-box diagonal.
double default_fraction(const char* name) { return core::incision_schema().find(name)->object_size->default_fraction; }
}  // namespace

core::IncisionParams incision_tool_defaults() {
  core::IncisionParams p;
  p.opening = -1.0;  // relative to the object until the user sets it
  return p;
}

nlohmann::json incision_draw_line(const std::string& object, const std::vector<glm::dvec2>& stroke_px,
                                  const core::IncisionParams& p, const std::optional<core::Camera>& view) {
  return core::IncisionDrawCommand::schema().to_json(core::IncisionDrawParams{object, stroke_px, view, p, {}});
}

ui::ToolEntry IncisionTool::entry() const {
  return {"Incision", "K", "Drag over a surface to cut an incision along the stroke (seed section 6.4)"};
}

void IncisionTool::activate(ToolContext&) {}

void IncisionTool::deactivate(ToolContext&) {
  gesture_.cancel();
  clear_preview();
  target_.clear();
  caster_.reset();
  caster_mesh_.reset();
}

void IncisionTool::clear_preview() {
  curve_.clear();
  preview_mesh_.reset();
  preview_lattice_.reset();
  preview_error_.clear();
  previewed_points_ = 0;
}

const core::SceneObject* IncisionTool::object(const ToolContext& ctx) const {
  const core::SceneObject* o = ctx.session.scene().find(target_);
  return o && o->world_mesh && !o->world_mesh->empty() ? o : nullptr;
}

core::IncisionParams IncisionTool::resolved(const core::SceneObject* o) const {
  core::IncisionParams p = params_;
  if (o)
    if (const auto it = typed_.find(o->name); it != typed_.end()) {
      if (it->second.width > 0.0) p.width = it->second.width;
      if (it->second.depth > 0.0) p.depth = it->second.depth;
      if (it->second.opening > 0.0) p.opening = it->second.opening > 1e-9 ? it->second.opening : 0.0;  // typed 0
    }
  const double diag =
      o && o->world_mesh && !o->world_mesh->empty() ? core::mesh_bounds(*o->world_mesh).diagonal() : 0.0;
  if (diag > 0.0) {
    if (p.width <= 0.0) p.width = default_fraction("width") * diag;
    if (p.depth <= 0.0) p.depth = default_fraction("depth") * diag;
    if (p.opening < 0.0) p.opening = default_fraction("opening") * diag;
  }
  return p;
}

const core::RayCaster* IncisionTool::caster_for(const core::SceneObject& o) {
  if (caster_mesh_ != o.world_mesh) {
    auto caster = std::make_unique<core::RayCaster>(core::BuildQuality::interactive);  // rebuilt after every cut
    caster->add_mesh(*o.world_mesh);
    caster->commit();
    caster_ = std::move(caster);
    caster_mesh_ = o.world_mesh;
  }
  return caster_.get();
}

void IncisionTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  const StrokeGesture::Event event = gesture_.update(in, ctx.view);
  if (event == StrokeGesture::Event::Began) {
    clear_preview();
    // The object under the cursor at mouse-down wins over the selection.
    target_ = ctx.selected;
    if (const auto name = pick(ctx, in.mouse_px)) target_ = *name;
  }
  // Throttled preview, also on frames without a move so the last points of a fast drag are shown.
  const std::size_t points = gesture_.points().size();
  if (gesture_.drawing() && points >= 2 && points != previewed_points_) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double, std::milli>(now - last_preview_).count() >= preview_interval_ms_) {
      // Nothing under the cursor at mouse-down and nothing selected: the first object the stroke passes over.
      if (target_.empty())
        if (const auto name = pick(ctx, in.mouse_px)) target_ = *name;
      update_preview(ctx);
      last_preview_ = now;
    }
  }
  if (event == StrokeGesture::Event::Ended) commit(ctx);
}

std::optional<std::string> IncisionTool::pick(const ToolContext& ctx, glm::dvec2 px) const {
  try {
    return pick_object(ctx.session.scene(), ctx.view, px);
  } catch (const std::exception& e) {  // non-finite mesh positions
    ctx.session.messages().error(std::string("incision: picking failed: ") + e.what());
    return std::nullopt;
  }
}

void IncisionTool::update_preview(const ToolContext& ctx) {
  if (gesture_.points().size() < 2 || gesture_.points().size() == previewed_points_) return;
  previewed_points_ = gesture_.points().size();
  const core::SceneObject* o = object(ctx);
  if (!o || !o->visible) {
    curve_.clear();
    preview_mesh_.reset();
    preview_lattice_.reset();
    preview_error_ = "no visible object to cut";
    return;
  }
  if (o->ffd || o->dffd || o->clip) {  // incision.draw rejects them: show the stroke only
    curve_.clear();
    preview_mesh_.reset();
    preview_lattice_.reset();
    preview_error_ = o->name + " is deformed by a lattice or a clip and cannot be cut";
    return;
  }
  try {
    const core::RayCaster* caster = caster_for(*o);
    const auto frame = core::fit_incision_frame(gesture_.points(), gesture_.view(), *caster);
    if (!frame) {
      curve_.clear();
      preview_mesh_.reset();
      preview_lattice_.reset();
      preview_error_ = "the stroke is not on " + o->name + " yet";
      return;
    }
    std::vector<glm::dvec3> curve;
    for (int i = 0; i < kCurveSamples; ++i) curve.push_back(frame->generator.eval(double(i) / (kCurveSamples - 1)));
    curve_ = std::move(curve);
    core::IncisionResult cut = core::incise(*o->world_mesh, *frame, resolved(o));
    preview_mesh_ = std::make_shared<const core::TriMesh>(std::move(cut.mesh));
    preview_lattice_ = std::make_shared<const core::TrivariateBSpline<glm::dvec3>>(std::move(cut.lattice));
    preview_error_.clear();
  } catch (const std::exception& e) {  // not yet across the surface, or parameters the command will reject
    preview_mesh_.reset();
    preview_lattice_.reset();
    preview_error_ = e.what();
  }
}

void IncisionTool::commit(ToolContext& ctx) {
  const core::Camera view = gesture_.view();
  std::vector<glm::dvec2> stroke = gesture_.take();
  clear_preview();
  if (stroke.size() < 2) return;  // a click, not a stroke
  const core::SceneObject* o = object(ctx);
  if (!o) {
    ctx.session.messages().error("incision.draw: start the stroke on an object or select the object to cut first");
    return;
  }
  const nlohmann::json line = incision_draw_line(o->name, stroke, resolved(o), view);
  EditorSession& session = ctx.session;  // outlives the deferred work; ctx may not
  const TypedSizes typed = typed_.count(o->name) ? typed_.at(o->name) : TypedSizes{};
  ctx.defer("Cutting " + o->name, [this, &session, line, name = o->name, stroke, view, typed]() {
    if (!session.execute(line)) return;  // errors go to the Log panel; the scene stays as it was
    const History& h = session.history();
    last_object_ = name, last_stroke_ = stroke, last_view_ = view, last_typed_ = typed;
    last_step_.mark(h);
  });
}

bool IncisionTool::last_is_top(const History& h) const {
  return last_step_.is_top(h, "incision.draw", last_object_, last_stroke_.size());
}

bool IncisionTool::rerun_last(ToolContext& ctx) {
  if (!last_is_top(ctx.session.history())) {
    if (!last_object_.empty())
      ctx.session.messages().info("Incision sizes apply to the next cut: the cut on '" + last_object_ +
                                  "' is not the latest step (undo what came after it to edit it)");
    return false;
  }
  EditorSession& s = ctx.session;
  ctx.defer("Re-cutting " + last_object_, [this, &s]() {
    if (!last_is_top(s.history()) || !s.undo()) return;
    const core::SceneObject* o = s.scene().find(last_object_);  // as it was before the cut
    if (!o || !s.execute(incision_draw_line(last_object_, last_stroke_, resolved(o), last_view_))) {
      s.redo();  // the edited cut failed (the Log says why): put the previous one back, and its sizes in the panel
      typed_[last_object_] = last_typed_;
      width_state_.limit.clear(), depth_state_.limit.clear(), opening_state_.limit.clear();  // not what is shown now
      return;
    }
    last_typed_ = typed_[last_object_];
    const History& h = s.history();
    last_step_.mark(h);
  });
  return true;
}

std::string IncisionTool::hint() const {
  if (gesture_.drawing()) return preview_mesh_ ? "Release to cut" : "Drag across the surface; release to cut";
  return "Drag over an object to cut an incision (the object under the cursor, else the selection)";
}

void IncisionTool::draw_panel(ToolContext& ctx) {
  // Sizes shown for the selected object (else the last one cut): incision.draw's declared size fields, each object
  // with its own; unset ones follow the object ("auto"). A value outside what the object takes is limited, and the
  // field says so (amber, the reason in its tooltip) and the Log once.
  const core::SceneObject* sel = ctx.session.scene().find(ctx.selected.empty() ? target_ : ctx.selected);
  const core::IncisionParams shown = resolved(sel);
  const double diag =
      sel && sel->world_mesh && !sel->world_mesh->empty() ? core::mesh_bounds(*sel->world_mesh).diagonal() : 0.0;
  TypedSizes no_object;
  TypedSizes& typed = sel ? typed_[sel->name] : no_object;
  const core::ParamSchema<core::IncisionParams>& schema = core::incision_schema();
  bool edited = false;
  auto size_field = [&](const char* name, double shown_value, ui::SizeFieldState& state) {
    const std::string limited =
        ui::size_param_widget(schema, name, typed, diag, shown_value, state, std::string("incision.") + name);
    if (!limited.empty())
      ctx.session.messages().warning("Incision " + std::string(name) + " " + ui::short_number(state.typed) + ": " +
                                     limited);
    edited |= state.committed;
  };
  size_field("width", shown.width, width_state_);
  size_field("depth", shown.depth, depth_state_);
  size_field("opening", shown.opening, opening_state_);
  const bool width_set = typed.width > 0.0 || params_.width > 0.0, depth_set = typed.depth > 0.0 || params_.depth > 0.0,
             opening_set = typed.opening > 0.0 || params_.opening >= 0.0;
  if (width_set || depth_set || opening_set) {
    if (ImGui::SmallButton("Defaults")) {
      params_.width = params_.depth = 0.0;
      params_.opening = incision_tool_defaults().opening;
      typed = TypedSizes{};
      width_state_.limit.clear(), depth_state_.limit.clear(), opening_state_.limit.clear();
      edited = true;
    }
    ui::tooltip("Back to sizes relative to the object (width, depth, opening)");
  }
  // An edited size re-runs the last cut when it is the newest step (one undoable step), else applies to the next.
  if (edited && sel && sel->name == last_object_)
    rerun_last(ctx);
  else if (edited && !last_object_.empty() && sel && sel->name != last_object_)
    ctx.session.messages().info("Incision sizes for '" + sel->name + "' apply to its next cut");
  if (last_is_top(ctx.session.history()) && sel && sel->name == last_object_)
    ImGui::TextColored(ui::colors::accent, "Editing the last cut of %s: size changes re-cut it", last_object_.c_str());
  ui::param_widget(schema, "walls", params_);
  ui::param_widget(schema, "order", params_);
  ui::param_widget(schema, "kernel", params_);

  ImGui::Spacing();
  static const KeyedWeightSection section{
      "Opening over time",
      {"incision_anim", "Opening",
       "Fraction of the opening as drawn: 0 closed (the cut faces touch), 1 as drawn; other values extrapolate",
       "Key the incision's opening at the two frames (one undoable incision.animate); press Space to play it",
       "Remove the keys: the incision shows fully open"},
      "Animating the incision of "};
  std::string unavailable;
  if (!sel)
    unavailable = "select an object cut by an incision";
  else if (!sel->morph)
    unavailable = "'" + sel->name + "' has no incision: cut one first (drag across it)";
  else if (sel->ffd || sel->dffd)
    unavailable = "'" + sel->name + "' is deformed; key the opening before placing it";
  const bool keyed = sel && sel->morph && (sel->morph->animated() || sel->morph->weight_at(0.0) != 1.0);
  draw_keyed_weight_section(ctx, section, core::IncisionAnimateCommand::schema(), opening_keys_, sel, unavailable,
                            keyed);
  ImGui::Separator();
  if (gesture_.drawing() && !preview_error_.empty())
    ImGui::TextColored(ui::colors::warning, "Preview: %s", preview_error_.c_str());
  ImGui::TextWrapped(
      "Left-drag across the surface (the object under the cursor, else the selected one): the cut is previewed "
      "while you drag; releasing cuts it as one undoable step.");
}

namespace {

// The preview's cut lattice (the opened local lattice of seed Eq. 6.2) drawn fainter than object lattices, with its
// C⁻¹ break at u = 1/2 marked as a discontinuity when the knots hold one there.
gpu::LatticeOverlay incision_lattice_overlay(std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice,
                                             const gpu::ViewStyle& style) {
  gpu::LatticeOverlay overlay{
      std::move(lattice), {}, {0.45f, 0.78f, 1.0f, 0.6f}, {0.92f, 0.96f, 1.0f, 0.8f}, 0.7f * style.lattice_point_px};
  const core::KnotVector& u = overlay.lattice->knots(0);
  const std::vector<double>& U = u.knots();
  const auto first = std::find(U.begin(), U.end(), 0.5);
  if (first != U.end() && u.multiplicity(0.5) == u.order()) {
    core::Discontinuity cut;
    cut.axis = 0;
    cut.u0 = 0.5;
    cut.plus_plane = static_cast<int>(first - U.begin());
    cut.minus_plane = cut.plus_plane - 1;
    overlay.discontinuities.push_back(cut);
  }
  return overlay;
}

}  // namespace

void IncisionTool::decorate(gpu::ViewOptions& options) const {
  if (!gesture_.drawing()) return;
  // G(v): a thick bright line on top; the stroke thinner over it, so it shows under the stroke.
  if (!curve_.empty()) options.overlays.curves.push_back({curve_, {0.4f, 1.0f, 0.3f, 1.0f}, 3.0f});
  gpu::ScreenStroke& stroke = options.add_stroke(gesture_.points());
  if (!curve_.empty()) stroke.width_px = std::min(stroke.width_px, 1.5f);
  if (preview_mesh_) options.overlays.meshes.push_back({target_, preview_mesh_});
  if (preview_lattice_) options.overlays.lattices.push_back(incision_lattice_overlay(preview_lattice_, options.style));
}

}  // namespace trispline::editor
