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
  // One key: its frame and its value, each a named field ("<id>.frame_<which>", "<id>.value_<which>").
  const auto key_rows = [&](const char* which, const char* frame_label, int* frame, double* value) {
    const std::string f = std::string("frame_") + which, v = std::string("value_") + which;
    row_label(frame_label);
    drag_int(("##" + f).c_str(), frame, 0.5f, 0, 100000);
    probe::item(id + "." + f);
    tooltip(which == std::string("from") ? "Timeline frame of the first key" : "Timeline frame of the second key");
    row_label(spec.value_label);
    drag_scalar(("##" + v).c_str(), ImGuiDataType_Double, value, 0.01f, nullptr, nullptr, "%.3f");
    probe::item(id + "." + v);
    tooltip(spec.value_tooltip);
  };
  key_rows("from", "From frame", &p.frame_from, &p.value_from);
  key_rows("to", "To frame", &p.frame_to, &p.value_to);
  row_label("Easing");
  if (ImGui::BeginCombo("##interp", p.interpolation.c_str())) {
    for (const char* name : {"linear", "constant", "smooth"})
      if (ImGui::Selectable(name, p.interpolation == name)) p.interpolation = name;
    ImGui::EndCombo();
  }
  tooltip(
      "How the value moves from the first key to the second (Blender's keyframe interpolation; smooth eases in "
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
