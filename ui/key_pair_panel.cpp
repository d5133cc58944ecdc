#include "ui/key_pair_panel.h"

#include <imgui.h>

#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"

namespace trispline::ui {

std::string key_pair_blocked(const KeyPairParams& p, const std::string& unavailable) {
  if (!unavailable.empty()) return unavailable;
  if (p.frame_from >= p.frame_to) return "the keys need frame from < frame to";
  return "";
}

std::vector<glm::dvec2> key_pair_keys(const KeyPairParams& p) {
  return {{double(p.frame_from), p.value_from}, {double(p.frame_to), p.value_to}};
}

KeyPairResult draw_key_pair_panel(KeyPairParams& p, const KeyPairSpec& spec, const std::string& unavailable,
                                  bool can_clear) {
  KeyPairResult r;
  const std::string id = spec.id;
  ImGui::PushID(spec.id);
  row_label("From frame");
  drag_int("##frame_from", &p.frame_from, 0.5f, 0, 100000);
  probe::item(id + ".frame_from");
  tooltip("Timeline frame of the first key");
  row_label(spec.value_label);
  drag_scalar("##value_from", ImGuiDataType_Double, &p.value_from, 0.01f, nullptr, nullptr, "%.3f");
  probe::item(id + ".value_from");
  tooltip(spec.value_tooltip);
  row_label("To frame");
  drag_int("##frame_to", &p.frame_to, 0.5f, 0, 100000);
  probe::item(id + ".frame_to");
  tooltip("Timeline frame of the second key");
  row_label(spec.value_label);
  drag_scalar("##value_to", ImGuiDataType_Double, &p.value_to, 0.01f, nullptr, nullptr, "%.3f");
  probe::item(id + ".value_to");
  tooltip(spec.value_tooltip);
  row_label("Easing");
  if (ImGui::BeginCombo("##interp", p.interpolation.c_str())) {
    for (const char* name : {"linear", "constant", "smooth"})
      if (ImGui::Selectable(name, p.interpolation == name)) p.interpolation = name;
    ImGui::EndCombo();
  }
  tooltip("How the value moves from the first key to the second (Blender's keyframe interpolation; smooth eases in "
          "and out)");
  const std::string blocked = key_pair_blocked(p, unavailable);
  ImGui::BeginDisabled(!blocked.empty());
  if (ImGui::Button("Animate")) r.animate = blocked.empty();
  ImGui::EndDisabled();
  probe::item(id + ".animate");
  tooltip(blocked.empty() ? spec.animate_tooltip : blocked.c_str());
  ImGui::SameLine();
  ImGui::BeginDisabled(!can_clear);
  if (ImGui::Button("Clear")) r.clear = can_clear;
  ImGui::EndDisabled();
  probe::item(id + ".clear");
  tooltip(spec.clear_tooltip);
  ImGui::PopID();
  return r;
}

}  // namespace trispline::ui
