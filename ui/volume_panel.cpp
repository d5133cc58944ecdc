#include "ui/volume_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/commands/volume_iso.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {

bool same_settings(const core::VolumeSilhouetteSettings& a, const core::VolumeSilhouetteSettings& b) {
  return a.enabled == b.enabled && a.style == b.style && a.hidden == b.hidden && a.projection == b.projection &&
         a.params.subdivision == b.params.subdivision && a.params.accuracy == b.params.accuracy;
}

void take_settings(const core::VolumeObject& v, VolumePanelState& s) {
  core::VolumeSilhouettesParams& p = s.silhouettes;
  p.object = v.name;
  p.enabled = v.silhouette.enabled;
  p.style = v.silhouette.style;
  p.hidden = v.silhouette.hidden;
  p.projection = v.silhouette.projection;
  p.subdivision = v.silhouette.params.subdivision;
  p.accuracy = v.silhouette.params.accuracy;
  s.seen = v.silhouette;
}

// A row of the info table: label, value, tooltip.
void info_row(const char* label, const std::string& value, const char* tip) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextColored(colors::dim, "%s", label);
  tooltip(tip);
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(value.c_str());
  tooltip(tip);
}

std::string number(double x, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

// Newton's stopping accuracy (the seed's second parameter) as powers of ten.
constexpr double kAccuracies[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};

bool accuracy_combo(core::VolumeSilhouettesParams& p) {
  const auto& schema = core::VolumeSilhouettesCommand::schema();
  const auto* f = schema.find("accuracy");
  row_label(f && !f->label.empty() ? f->label.c_str() : "Accuracy");
  bool changed = false;
  if (ImGui::BeginCombo("##accuracy", number(p.accuracy, "%.0e").c_str())) {
    for (double a : kAccuracies) {
      if (ImGui::Selectable(number(a, "%.0e").c_str(), a == p.accuracy) && a != p.accuracy) {
        p.accuracy = a;
        changed = true;
      }
      probe::item("volume.silhouettes.accuracy." + number(a, "%.0e"));
    }
    ImGui::EndCombo();
  }
  probe::item("volume.silhouettes.accuracy");
  if (f) tooltip(param_tooltip(f->doc).c_str());
  return changed;
}

// The Render section's values from the volume: its mode, step and transfer function (the default one it would get
// when it has none yet).
void take_render(const core::VolumeObject& v, VolumePanelState& s) {
  core::VolumeRenderParams& p = s.render;
  p.object = v.name;
  p.mode = v.render_mode;
  p.transfer = v.transfer.points.empty() ? core::default_transfer_function(v) : v.transfer;
  p.step = v.dvr_step;
  s.seen_render = p;
  s.seen_render.transfer = v.transfer;
}

bool same_render(const core::VolumeObject& v, const core::VolumeRenderParams& seen) {
  return v.render_mode == seen.mode && v.dvr_step == seen.step && seen.transfer && v.transfer == *seen.transfer;
}

// Presets of the transfer function, in the Preset combo's order.
struct TransferPreset {
  const char* name;
  const char* tooltip;
  core::TransferFunction (*make)(const core::VolumeObject&);
};
constexpr TransferPreset kTransferPresets[] = {
    {"CT: skin and bone",
     "Hounsfield units: air transparent, skin and soft tissue a faint orange veil (-400 to 100 HU), bone opaque ivory "
     "from 250 HU",
     [](const core::VolumeObject&) { return core::ct_transfer_function(); }},
    {"Ramp from the iso-level",
     "Transparent at the iso-level, a faint warm tint a quarter of the way up, opaque white at the largest value",
     [](const core::VolumeObject& v) {
       core::VolumeObject plain = v;
       plain.units.clear();  // not the CT preset
       return core::default_transfer_function(plain);
     }},
};

// The Render section: mode, and for direct volume rendering the transfer function and the step. True when a
// volume.render line is to be executed (state.render holds it).
bool render_section(const core::VolumeObject& v, VolumePanelState& state, double lo, double hi, double speed,
                    const char* value_format) {
  core::VolumeRenderParams& p = state.render;
  const auto& schema = core::VolumeRenderCommand::schema();
  bool commit = param_widget(schema, "mode", p);
  if (p.mode != core::VolumeObject::RenderMode::dvr) return commit;
  std::vector<core::TransferPoint>& pts = p.transfer->points;
  ImGui::TextColored(colors::dim, "Transfer function");
  if (const auto* f = schema.find("transfer")) tooltip(param_tooltip(f->doc).c_str());
  int remove = -1;
  if (ImGui::BeginTable("##transfer", 3, ImGuiTableFlags_SizingStretchProp)) {
    for (int i = 0; i < int(pts.size()); ++i) {
      ImGui::PushID(i);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      // Each value stays between its neighbours (the function's values increase).
      const double step = std::max(speed, 1e-9) * 1e-3;
      const double min = i > 0 ? pts[i - 1].value + step : std::min(lo, pts[i].value);
      const double max = i + 1 < int(pts.size()) ? pts[i + 1].value - step : std::max(hi, pts[i].value);
      ImGui::SetNextItemWidth(-1.0f);
      drag_scalar("##value", ImGuiDataType_Double, &pts[i].value, float(speed), &min, &max, value_format,
                  ImGuiSliderFlags_AlwaysClamp);
      probe::item("volume.transfer." + std::to_string(i));
      tooltip("The value of D this point is at (the volume's units); drag, or click to type. Applied on release.");
      commit |= ImGui::IsItemDeactivatedAfterEdit();
      ImGui::TableNextColumn();
      float rgba[4] = {float(pts[i].rgba.x), float(pts[i].rgba.y), float(pts[i].rgba.z), float(pts[i].rgba.w)};
      if (ImGui::ColorEdit4("##rgba", rgba,
                            ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_AlphaBar |
                                ImGuiColorEditFlags_AlphaPreviewHalf | ImGuiColorEditFlags_Float))
        pts[i].rgba = glm::dvec4(rgba[0], rgba[1], rgba[2], rgba[3]);
      probe::item("volume.transfer." + std::to_string(i) + ".color");
      tooltip("Colour (linear RGB) and opacity per index unit of path (alpha) at this value; click to edit");
      commit |= ImGui::IsItemDeactivatedAfterEdit();
      ImGui::SameLine();
      ImGui::Text("a %.3f", pts[i].rgba.w);
      ImGui::TableNextColumn();
      ImGui::BeginDisabled(pts.size() <= 2);
      if (ImGui::SmallButton("x")) remove = i;
      ImGui::EndDisabled();
      probe::item("volume.transfer." + std::to_string(i) + ".remove");
      tooltip("Remove this point (a transfer function keeps at least 2)");
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  if (remove >= 0) {
    pts.erase(pts.begin() + remove);
    commit = true;
  }
  ImGui::BeginDisabled(pts.size() >= std::size_t(core::kMaxTransferPoints));
  if (ImGui::Button("Add point")) {
    // Halfway between the last two points, with their mean colour: the function does not change until edited.
    const core::TransferPoint& a = pts[pts.size() - 2];
    const core::TransferPoint& b = pts.back();
    pts.insert(pts.end() - 1, core::TransferPoint{0.5 * (a.value + b.value), 0.5 * (a.rgba + b.rgba)});
    commit = true;
  }
  ImGui::EndDisabled();
  probe::item("volume.transfer.add");
  tooltip("Add a point halfway between the last two (at most 16)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::BeginCombo("##preset", "Preset...")) {
    for (const TransferPreset& preset : kTransferPresets) {
      if (ImGui::Selectable(preset.name)) {
        p.transfer = preset.make(v);
        commit = true;
      }
      probe::item(std::string("volume.transfer.preset.") + preset.name);
      tooltip(preset.tooltip);
    }
    ImGui::EndCombo();
  }
  probe::item("volume.transfer.preset");
  tooltip("Replace the transfer function with a preset");
  if (const auto* f = schema.find("step")) {
    row_label(f->label.c_str());
    const double min = f->range.lo, max = f->range.hi;
    drag_scalar("##step", ImGuiDataType_Double, &p.step, float(f->ui_step), &min, &max, f->ui_format.c_str(),
                ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
    probe::item("volume.render.step");
    tooltip(param_tooltip(f->doc).c_str());
    commit |= ImGui::IsItemDeactivatedAfterEdit();
  }
  return commit;
}

// The Volume panel's further levels: level, style, colour and remove per level, then Add level.
void more_levels_section(const core::VolumeObject& v, VolumePanelState& state, VolumePanelResult& r, double lo,
                         double hi, double speed, const char* format) {
  ImGui::Separator();
  ImGui::TextColored(colors::dim, "More levels");
  tooltip(
      "Further iso-levels drawn as silhouettes only, each in its own style and colour (seed Figs. 7.4-7.6, 7.12: "
      "skin and bone together). The surface is the first level's. Each change is one volume.iso with every level.");
  const auto& styles = core::VolumeSilhouettesCommand::schema().find("style")->choices;
  for (std::size_t i = 0; i < v.more_levels.size() && i < state.more_iso.size(); ++i) {
    const core::VolumeIsoLevel& l = v.more_levels[i];
    const std::string id = "volume.levels." + std::to_string(i + 1);
    const int k = int(i);
    ImGui::PushID(k);
    row_label(("Level " + std::to_string(i + 2)).c_str());
    drag_scalar("##level", ImGuiDataType_Double, &state.more_iso[i], float(speed), &lo, &hi, format,
                ImGuiSliderFlags_AlwaysClamp);
    probe::item(id);
    tooltip("This level's value; release or Enter to apply");
    if (ImGui::IsItemDeactivatedAfterEdit() && std::isfinite(state.more_iso[i]) && state.more_iso[i] != l.iso)
      r.line = volume_levels_line(v, k, [level = state.more_iso[i]](core::VolumeLevelSpec& s) { s.level = level; });
    row_label("");
    const float square = ImGui::GetFrameHeight(), gap = ImGui::GetStyle().ItemInnerSpacing.x;
    ImGui::SetNextItemWidth(std::max(ImGui::CalcItemWidth() - 2.0f * (square + gap) - ImGui::GetFontSize(), square));
    if (ImGui::BeginCombo("##style", l.style.c_str())) {
      for (const std::string& st : styles) {
        if (ImGui::Selectable(st.c_str(), st == l.style) && st != l.style)
          r.line = volume_levels_line(v, k, [st](core::VolumeLevelSpec& s) { s.style = st; });
        probe::item(id + ".style." + st);
      }
      ImGui::EndCombo();
    }
    probe::item(id + ".style");
    tooltip("This level's stroke style (as Style above; plain and width use the level's colour)");
    ImGui::SameLine(0.0f, gap);
    float color[3] = {l.color.x, l.color.y, l.color.z};
    ImGui::ColorEdit3("##color", color, ImGuiColorEditFlags_NoInputs);
    probe::item(id + ".color");
    tooltip("This level's stroke colour (plain strokes; the darkest of width strokes)");
    if (ImGui::IsItemDeactivatedAfterEdit())
      r.line = volume_levels_line(
          v, k, [c = glm::vec3(color[0], color[1], color[2])](core::VolumeLevelSpec& s) { s.color = c; });
    ImGui::SameLine(0.0f, gap);
    if (ImGui::Button("x", ImVec2(square, square))) r.line = volume_levels_line(v, k, nullptr, true);
    probe::item(id + ".remove");
    tooltip("Remove this level");
    ImGui::PopID();
  }
  ImGui::BeginDisabled(1 + v.more_levels.size() >= core::kMaxVolumeLevels);
  if (ImGui::Button("Add level")) {
    // A quarter of the value range below the surface's level (towards soft tissue on CT), inside the range.
    const double add = std::clamp(v.iso - 0.25 * (hi - lo), lo, hi);
    r.line = volume_levels_line(v, -1, nullptr, false, add);
  }
  ImGui::EndDisabled();
  probe::item("volume.levels.add");
  tooltip("Add an iso-level whose silhouettes are drawn with the surface's (at most 8 levels); set its value after");
}

}  // namespace

nlohmann::json volume_levels_line(const core::VolumeObject& v, int k,
                                  const std::function<void(core::VolumeLevelSpec&)>& edit, bool remove,
                                  std::optional<double> add) {
  core::VolumeIsoParams p;
  p.object = v.name;
  p.level = v.iso;
  std::vector<core::VolumeLevelSpec> levels{{v.iso, std::nullopt, std::nullopt}};
  for (std::size_t i = 0; i < v.more_levels.size(); ++i) {
    core::VolumeLevelSpec s{v.more_levels[i].iso, v.more_levels[i].style, v.more_levels[i].color};
    if (int(i) == k && remove) continue;
    if (int(i) == k && edit) edit(s);
    levels.push_back(std::move(s));
  }
  if (add) levels.push_back({*add, std::nullopt, std::nullopt});
  p.levels = std::move(levels);
  return core::VolumeIsoCommand::schema().to_json(p);
}

std::string volume_spacing_text(const core::VolumeSpline& spline) {
  const glm::dmat4& m = spline.index_to_world();
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.3g × %.3g × %.3g mm", glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                glm::length(glm::dvec3(m[2])));
  return buf;
}

VolumePanelResult draw_volume_panel(const Rect& rect, const core::VolumeObject& v, VolumePanelState& state,
                                    const VolumeLiveInfo& live) {
  VolumePanelResult r;
  if (state.volume != v.name) {
    state.volume = v.name;
    take_render(v, state);
    state.iso = state.seen_iso = v.iso;
    state.more_iso.clear(), state.seen_more_iso.clear();
    take_settings(v, state);
  }
  if (v.iso != state.seen_iso) state.iso = state.seen_iso = v.iso;  // a command changed it (undo, a replayed log)
  if (!same_settings(v.silhouette, state.seen)) take_settings(v, state);
  if (!same_render(v, state.seen_render) && !ImGui::IsAnyItemActive()) take_render(v, state);

  if (begin_docked("Volume", rect)) {
    {
      const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
      probe::rect("panel.volume", pos, ImVec2(pos.x + size.x, pos.y + size.y));
    }
    ImGui::TextUnformatted(v.name.c_str());
    tooltip("The selected volume (its id in command lines)");
    if (!v.modality.empty()) {
      ImGui::SameLine();
      ImGui::TextColored(colors::dim, "%s", v.modality.c_str());
      tooltip("Modality, as the file says (DICOM 0008,0060)");
    }
    const std::string units = v.units.empty() ? std::string() : " " + v.units;
    if (ImGui::BeginTable("##volume_info", 2, ImGuiTableFlags_SizingStretchProp)) {
      const auto& d = v.spline->dims();
      info_row("Grid", std::to_string(d[0]) + " × " + std::to_string(d[1]) + " × " + std::to_string(d[2]) + " samples",
               "Samples per axis of the volume (voxels); each is a control point of the spline D (seed Eq. 7.1)");
      info_row("Spacing", volume_spacing_text(*v.spline),
               "Distance between neighbouring samples along each index axis, millimetres (world units)");
      info_row("Values",
               "[" + number(v.table->range_min(), "%.4g") + ", " + number(v.table->range_max(), "%.4g") + "]" +
                   (v.units.empty() ? std::string(" (no unit)") : units),
               "Range of D over the volume (its control points' bounds): HU for CT, the scanner's units for MR");
      info_row("Spline",
               "order " + std::to_string(v.spline->order()) +
                   (v.spline->interpolating() ? ", interpolating" : ", control points = samples"),
               "Order per axis (degree + 1) of the trivariate B-spline D; 'control points = samples' smooths noise "
               "(the seed's choice), 'interpolating' passes through every sample");
      info_row("File", std::filesystem::path(v.source).filename().string(), v.source.c_str());
      ImGui::EndTable();
    }

    ImGui::Separator();
    const double lo = v.table->range_min(), hi = v.table->range_max();
    const double speed = hi > lo ? (hi - lo) / 400.0 : 1.0;
    std::string format = "%.2f" + units;
    for (std::size_t i = 4; i < format.size(); ++i)
      if (format[i] == '%') format.insert(i++, "%");  // a '%' in the unit text is printed, not a conversion
    row_label("Iso-level");
    drag_scalar("##iso", ImGuiDataType_Double, &state.iso, float(speed), &lo, &hi, format.c_str(),
                ImGuiSliderFlags_AlwaysClamp);
    probe::item("volume.iso");
    if (const auto* f = core::VolumeIsoCommand::schema().find("level"))
      tooltip((param_tooltip(f->doc) + "\nDrag to preview the surface live, release to apply (volume.iso); a click "
                                       "types a value. The silhouettes follow the level.")
                  .c_str());
    if (ImGui::IsItemActive() && state.iso != v.iso) r.iso_preview = state.iso;
    if (ImGui::IsItemDeactivatedAfterEdit() && std::isfinite(state.iso) && state.iso != v.iso)
      r.line = core::VolumeIsoCommand::schema().to_json(core::VolumeIsoParams{v.name, state.iso});

    // Further levels' fields follow the volume unless one is being edited.
    std::vector<double> more;
    for (const core::VolumeIsoLevel& l : v.more_levels) more.push_back(l.iso);
    if (more != state.seen_more_iso && !ImGui::IsAnyItemActive()) state.more_iso = state.seen_more_iso = more;
    more_levels_section(v, state, r, lo, hi, speed, format.c_str());

    ImGui::Separator();
    ImGui::TextColored(colors::dim, "Render");
    tooltip(
        "How the volume is drawn: its iso-surface, or direct volume rendering through a transfer function (seed "
        "section 7.4)");
    if (render_section(v, state, lo, hi, speed, format.c_str()))
      r.line = core::VolumeRenderCommand::schema().to_json(state.render);

    ImGui::Separator();
    ImGui::TextColored(colors::dim, "Silhouettes");
    tooltip(
        "The iso-surface's smooth silhouettes for the current view, found by Newton steps in the singletons "
        "holding the level (seed section 7.3.3)");
    core::VolumeSilhouettesParams& p = state.silhouettes;
    p.object = v.name;
    const auto& schema = core::VolumeSilhouettesCommand::schema();
    bool commit = false;
    if (const auto* f = schema.find("enabled")) {
      const ParamWidget w{schema.id(),           &f->doc,    "Show",      f->kind, f->range, &f->choices,
                          int(f->choice_member), f->ui_step, f->ui_format};
      commit |= param_widget(w, &p.enabled);
    }
    ImGui::BeginDisabled(!p.enabled);
    for (const char* field : {"style", "hidden", "projection", "subdivision"}) commit |= param_widget(schema, field, p);
    commit |= accuracy_combo(p);
    ImGui::EndDisabled();
    if (p.enabled) {
      if (live.extracting && live.ms < 0)
        ImGui::TextColored(colors::dim, "extracting...");
      else if (live.ms >= 0)
        ImGui::TextColored(colors::dim, "%zu points, %.0f ms%s", live.points, live.ms,
                           live.extracting ? " (updating...)"
                           : live.current  ? ""
                                           : " (previous view)");
      tooltip(
          "The silhouettes drawn: points found for the current view and their extraction time on a worker "
          "thread (the view stays interactive; a new view is extracted when the last one is done)");
    }
    if (commit) r.line = schema.to_json(p);

    ImGui::Separator();
    ImGui::TextColored(colors::dim, "Export");
    tooltip("Write the silhouettes or the iso-surface to a file (volume.export)");
    const char* group = "";
    for (const VolumeExportKind& k : kVolumeExports) {
      if (std::string(group) != k.what) {
        group = k.what;
        row_label(std::string(k.what) == "iso" ? "Iso-surface" : "Silhouettes");
      } else {
        ImGui::SameLine();
      }
      if (ImGui::Button(k.label)) r.export_kind = &k;
      probe::item(std::string("volume.export.") + k.id);
      tooltip(k.tooltip);
    }
  }
  ImGui::End();
  return r;
}

}  // namespace trispline::ui
