#include "ui/placement_panel.h"

#include <imgui.h>

#include <algorithm>

#include "ui/gui_probe.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

PlacementPanelState PlacementPanelState::from(const core::PlaceSketchParams& p) {
  PlacementPanelState st;
  st.width_curve = p.width_profile.size() >= 2 ? curve_from_samples(p.width_profile) : flat_curve();
  st.height_curve = !p.height_profile.empty() && p.height_profile[0].size() >= 2
                        ? curve_from_samples(p.height_profile[0])
                        : flat_curve();
  if (p.springs) st.springs = *p.springs;
  return st;
}

PlacementPanelResult draw_placement_panel(core::PlaceSketchParams& p, PlacementPanelState& st,
                                          const std::vector<std::string>& objects) {
  using Cmd = core::PlaceSketchCommand;
  const core::ParamSchema<core::PlaceSketchParams>& schema = Cmd::schema();
  PlacementPanelResult r;
  auto field = [&](const char* name) { r.committed |= param_widget(schema, name, p); };

  row_label("Object");
  if (ImGui::BeginCombo("##object", p.object.empty() ? "(choose)" : p.object.c_str())) {
    for (const std::string& name : objects) {
      if (ImGui::Selectable(name.c_str(), name == p.object) && name != p.object) {
        p.object = name;
        r.object_changed = true;
      }
    }
    ImGui::EndCombo();
  }
  tooltip("The object to place along the stroke (defaults to the selected object)");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Volume");
  ImGui::Separator();
  field("width");
  field("height");
  field("volume");
  field("fit");
  field("extent");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Width profile d(u)");
  ImGui::Separator();
  if (curve_editor("width_profile", st.width_curve, schema.find("width_profile")->doc.help.c_str(), 70.0f)) {
    r.committed = true;
  }
  ImGui::TextColored(colors::dim, "Height profile h(u)");
  ImGui::Separator();
  if (curve_editor("height_profile", st.height_curve, schema.find("height_profile")->doc.help.c_str(), 70.0f)) {
    r.committed = true;
  }
  p.width_profile = profile_samples(st.width_curve);
  p.height_profile.clear();
  if (std::vector<double> h = profile_samples(st.height_curve); !h.empty()) p.height_profile.push_back(std::move(h));

  ImGui::Spacing();
  if (ImGui::CollapsingHeader("Contact springs")) {
    bool on = p.springs.has_value();
    if (ImGui::Checkbox("Relax the contact surface", &on)) r.committed = true;
    probe::item("place.sketch.springs");
    tooltip(schema.find("springs")->doc.help.c_str());
    ImGui::BeginDisabled(!on);
    const core::ParamSchema<core::SpringParams>& springs = core::spring_schema();
    for (const auto& f : springs.fields())
      if (f.member) r.committed |= param_widget(springs, f.doc.name, st.springs);
    ImGui::EndDisabled();
    p.springs = on ? std::optional<core::SpringParams>(st.springs) : std::nullopt;
  }

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Contact sampling");
  ImGui::Separator();
  field("samples");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Lattice");
  ImGui::Separator();
  field("order");
  field("controls");
  // Orders at most the control count, and at least as many contact rays as control points along u and v.
  for (int a = 0; a < 3; ++a) p.order[a] = std::min(p.order[a], p.controls[a]);
  for (int a = 0; a < 2; ++a) p.samples[a] = std::max(p.samples[a], p.controls[a]);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Object axes");
  ImGui::Separator();
  field("length_axis");
  field("up_axis");
  if (p.up_axis == p.length_axis) ImGui::TextColored(colors::warning, "Length and up axes must differ.");

  ImGui::Spacing();
  if (ImGui::Button("Defaults")) {
    core::PlaceSketchParams defaults;
    defaults.object = p.object;
    p = defaults;
    st = PlacementPanelState{};
    r.reset = r.committed = true;
  }
  tooltip("Reset every parameter to its default");
  return r;
}

}  // namespace trispline::ui
