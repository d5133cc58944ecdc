#include "ui/history_panel.h"

#include <imgui.h>

#include <algorithm>

#include "ui/gui_probe.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {

constexpr const char* kRunAgain = "Run again";

// Width a row's selectable leaves for a "Run again" button on its right.
float row_width(bool with_button) {
  const float avail = ImGui::GetContentRegionAvail().x;
  if (!with_button) return 0.0f;  // the whole row
  const ImGuiStyle& st = ImGui::GetStyle();
  return std::max(40.0f, avail - ImGui::CalcTextSize(kRunAgain).x - 2 * st.FramePadding.x - st.ItemSpacing.x);
}

// The "Run again" button at the end of a row; true when pressed.
bool run_again_button(const std::string& probe_name, const std::string& path) {
  ImGui::SameLine();
  const bool pressed = ImGui::SmallButton(kRunAgain);
  probe::item(probe_name);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Opening a log or recovering a session never writes files: this entry was replayed without "
        "writing %s.\nRun again writes it now, as it was at this step (no new history step).",
        path.c_str());
  return pressed;
}

}  // namespace

std::string not_written_label(const std::string& label) { return label + " \xE2\x80\x94 not written again"; }

HistoryPanelResult draw_history_panel(const Rect& rect, const HistoryView& view) {
  HistoryPanelResult result;
  if (begin_docked("History", rect)) {
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    probe::rect("panel.history", pos, ImVec2(pos.x + size.x, pos.y + size.y));
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
    // Row n means "n commands applied": row 0 is the empty document. The actions that ran at n follow it.
    for (std::size_t n = 0; n <= view.labels.size(); ++n) {
      const bool current = n == view.applied;
      const bool undone = n > view.applied;
      const bool unwritten = n > 0 && n - 1 < view.not_written.size() && view.not_written[n - 1];
      std::string text = n == 0 ? std::string("(initial state)") : std::to_string(n) + "  " + view.labels[n - 1];
      if (unwritten) text = not_written_label(text);
      if (undone) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      ImGui::PushID(static_cast<int>(n));
      if (ImGui::Selectable(text.c_str(), current, 0, ImVec2(row_width(unwritten), 0)) && !current) result.jump_to = n;
      probe::item("history.row." + std::to_string(n));
      if (ImGui::IsItemHovered() && !current) ImGui::SetTooltip(undone ? "Redo up to here" : "Undo back to here");
      if (unwritten) {
        const std::string path = n - 1 < view.paths.size() ? view.paths[n - 1] : std::string();
        if (run_again_button("history.run_again." + std::to_string(n), path)) result.run_again = n - 1;
      }
      ImGui::PopID();
      if (undone) ImGui::PopStyleColor();
      if (current && ImGui::IsWindowAppearing()) ImGui::SetScrollHereY();
      for (std::size_t k = 0; k < view.outputs.size(); ++k) {
        const HistoryOutputRow& o = view.outputs[k];
        if (o.after != n) continue;
        ImGui::PushID(static_cast<int>(view.labels.size() + 1 + k));
        ImGui::Indent();
        const std::string label = o.not_written ? not_written_label(o.label) : o.label;
        const bool with_button = o.not_written && o.can_run_again;
        // The label is clipped where the button begins, so the button always stays inside the panel.
        const ImVec2 at = ImGui::GetCursorScreenPos();
        const float width = with_button ? row_width(true) : ImGui::GetContentRegionAvail().x;
        const ImVec2 end(at.x + width, at.y + ImGui::GetTextLineHeight());
        ImGui::Dummy(ImVec2(width, ImGui::GetTextLineHeight()));
        ImDrawList* draw = ImGui::GetWindowDrawList();
        draw->PushClipRect(at, end, true);
        draw->AddText(at, ImGui::GetColorU32(undone ? ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled) : colors::dim),
                      label.c_str());
        draw->PopClipRect();
        probe::item("history.output." + std::to_string(k));
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("%s\nNot an undo step: it writes files (%s)", label.c_str(), o.path.c_str());
        if (with_button && run_again_button("history.output_run_again." + std::to_string(k), o.path))
          result.run_again_output = k;
        ImGui::Unindent();
        ImGui::PopID();
      }
    }
    ImGui::EndChild();
  }
  ImGui::End();
  return result;
}

}  // namespace trispline::ui
