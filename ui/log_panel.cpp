#include "ui/log_panel.h"

#include <imgui.h>

#include <cstring>

#include "ui/gui_probe.h"
#include "ui/theme.h"

namespace trispline::ui {

void LogPanel::draw(const Rect& rect, MessageLog& log) {
  if (begin_docked("Log", rect)) {
    {
      const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
      probe::rect("panel.log", pos, ImVec2(pos.x + size.x, pos.y + size.y));
    }
    if (ImGui::SmallButton("Clear")) log.clear();
    ImGui::SameLine();
    ImGui::Checkbox("Errors only", &errors_only_);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(180);
    ImGui::InputTextWithHint("##filter", "filter", filter_, sizeof filter_);
    ImGui::Separator();
    ImGui::BeginChild("##messages", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
    const bool at_bottom = ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 4.0f;
    for (const Message& m : log.messages()) {
      if (errors_only_ && m.severity != Severity::Error) continue;
      if (filter_[0] && m.text.find(filter_) == std::string::npos) continue;
      ImGui::TextColored(colors::dim, "%s", m.time.c_str());
      ImGui::SameLine();
      if (m.severity == Severity::Info) {
        ImGui::TextUnformatted(m.text.c_str());
      } else {
        const ImVec4& c = m.severity == Severity::Error ? colors::error : colors::warning;
        ImGui::PushStyleColor(ImGuiCol_Text, c);
        ImGui::TextUnformatted(m.text.c_str());
        ImGui::PopStyleColor();
      }
    }
    if (log.generation() != seen_generation_) {
      if (at_bottom || seen_generation_ == 0) ImGui::SetScrollHereY(1.0f);
      seen_generation_ = log.generation();
    }
    ImGui::EndChild();
  }
  ImGui::End();
}

}  // namespace trispline::ui
