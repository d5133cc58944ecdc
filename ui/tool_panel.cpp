#include "ui/tool_panel.h"

#include <imgui.h>

namespace trispline::ui {

bool begin_tool_panel(const Rect& rect, const std::vector<ToolEntry>& tools, int* active) {
  if (!begin_docked("Tool", rect)) return false;
  const float w = ImGui::GetContentRegionAvail().x;
  for (int i = 0; i < int(tools.size()); ++i) {
    const bool on = i == *active;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_HeaderActive));
    if (ImGui::Button(tools[i].name.c_str(), ImVec2(w, 0))) *active = i;
    if (on) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", tools[i].tooltip.c_str(), tools[i].shortcut.c_str());
  }
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::Spacing();
  return true;
}

void end_tool_panel() { ImGui::End(); }

}  // namespace trispline::ui
