#include "ui/history_panel.h"

#include "ui/theme.h"

#include <imgui.h>

namespace trispline::ui {

HistoryPanelResult draw_history_panel(const Rect& rect, const HistoryView& view) {
  HistoryPanelResult result;
  if (begin_docked("History", rect)) {
    ImGui::BeginDisabled(!view.can_undo);
    if (ImGui::Button("Undo")) result.undo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!view.can_redo);
    if (ImGui::Button("Redo")) result.redo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextColored(colors::dim, "%zu / %zu", view.applied, view.labels.size());
    ImGui::Separator();
    ImGui::BeginChild("##history");
    // Row n means "n commands applied": row 0 is the empty document.
    for (std::size_t n = 0; n <= view.labels.size(); ++n) {
      const bool current = n == view.applied;
      const bool undone = n > view.applied;
      const std::string text = n == 0 ? std::string("(initial state)") : std::to_string(n) + "  " + view.labels[n - 1];
      if (undone) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      ImGui::PushID(static_cast<int>(n));
      if (ImGui::Selectable(text.c_str(), current) && !current) result.jump_to = n;
      if (ImGui::IsItemHovered() && !current) ImGui::SetTooltip(undone ? "Redo up to here" : "Undo back to here");
      ImGui::PopID();
      if (undone) ImGui::PopStyleColor();
      if (current && ImGui::IsWindowAppearing()) ImGui::SetScrollHereY();
    }
    ImGui::EndChild();
  }
  ImGui::End();
  return result;
}

}  // namespace trispline::ui
