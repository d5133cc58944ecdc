#include "ui/status_bar.h"

#include <imgui.h>

#include <algorithm>

#include "ui/theme.h"

namespace trispline::ui {

float status_bar_height() { return ImGui::GetFrameHeight() + 2.0f; }

void draw_status_bar(const StatusInfo& s) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float h = status_bar_height();
  ImGui::SetNextWindowPos(ImVec2(0, display.y - h));
  ImGui::SetNextWindowSize(ImVec2(display.x, h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 3));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImGui::GetStyleColorVec4(ImGuiCol_MenuBarBg));
  const int flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                    ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (ImGui::Begin("##status_bar", nullptr, flags)) {
    ImGui::Text("%s%s", s.document.c_str(), s.modified ? " *" : "");
    ImGui::SameLine(0, 24);
    ImGui::TextColored(colors::dim, "Objects %zu   Vertices %zu   Triangles %zu", s.objects, s.vertices, s.triangles);
    if (s.last_command_ms >= 0) {
      ImGui::SameLine(0, 24);
      ImGui::TextColored(colors::dim, "Last: %s %.1f ms", s.last_command.c_str(), s.last_command_ms);
    }
    if (!s.hint.empty()) {
      const float w = ImGui::CalcTextSize(s.hint.c_str()).x;
      ImGui::SameLine(std::max(ImGui::GetCursorPosX() + 24, display.x - w - 12));
      ImGui::TextColored(colors::dim, "%s", s.hint.c_str());
    }
  }
  ImGui::End();
  ImGui::PopStyleColor();
  ImGui::PopStyleVar(2);
}

}  // namespace trispline::ui
