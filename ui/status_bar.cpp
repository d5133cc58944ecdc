#include "ui/status_bar.h"

#include <imgui.h>

#include <algorithm>
#include <string>

#include "core/base/text.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {

// `text` cut at a character boundary to fit `width` pixels, ending in "..." when cut ("" when not even that fits).
std::string elided(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  std::string cut = text;
  while (!cut.empty()) {
    // Drops the last character: its continuation bytes (10xxxxxx), then its lead byte.
    while (!cut.empty() && (static_cast<unsigned char>(cut.back()) & 0xC0) == 0x80) cut.pop_back();
    if (!cut.empty()) cut.pop_back();
    const std::string shown = cut + "...";
    if (ImGui::CalcTextSize(shown.c_str()).x <= width) return shown;
  }
  return {};
}

}  // namespace

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
    // The tool's hint is right-aligned and wins the room: the last command's text is cut ("...") before it.
    const float hint_x = display.x - (s.hint.empty() ? 0.0f : ImGui::CalcTextSize(s.hint.c_str()).x + 12);
    const float last_end = s.hint.empty() ? display.x - 8 : hint_x - 24;
    ImGui::Text("%s%s", s.document.c_str(), s.modified ? " *" : "");
    ImGui::SameLine(0, 24);
    ImGui::TextColored(colors::dim, "Objects %zu   Vertices %zu   Triangles %zu", s.objects, s.vertices, s.triangles);
    if (s.last_command_ms >= 0) {
      ImGui::SameLine(0, 24);
      const std::string last = elided("Last: " + s.last_command + core::printf_string(" %.1f ms", s.last_command_ms),
                                      last_end - ImGui::GetCursorPosX());
      ImGui::TextColored(colors::dim, "%s", last.c_str());
    }
    if (!s.hint.empty()) {
      ImGui::SameLine(0, 24);
      if (ImGui::GetCursorPosX() < hint_x) ImGui::SetCursorPosX(hint_x);
      ImGui::TextColored(colors::dim, "%s", s.hint.c_str());
    }
  }
  ImGui::End();
  ImGui::PopStyleColor();
  ImGui::PopStyleVar(2);
}

}  // namespace trispline::ui
