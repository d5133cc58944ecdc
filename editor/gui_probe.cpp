#include "editor/gui_probe.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <fstream>
#include <system_error>

#include "ui/gui_probe.h"

namespace fs = std::filesystem;

namespace trispline::editor {

nlohmann::json imgui_probe_fields() {
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  nlohmann::json popups = nlohmann::json::array();
  for (const ImGuiPopupData& p : g.OpenPopupStack) popups.push_back(p.Window ? p.Window->Name : "(opening)");
  nlohmann::json items = nlohmann::json::object();
  for (const auto& [name, r] : ui::probe::items()) items[name] = {r.min.x, r.min.y, r.max.x, r.max.y};
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [name, text] : ui::probe::values()) values[name] = text;
  bool tooltip = false;  // a tooltip is drawn this frame
  for (const ImGuiWindow* w : g.Windows) tooltip = tooltip || ((w->Flags & ImGuiWindowFlags_Tooltip) && w->Active);
  return {{"popups", popups},
          {"tooltip", tooltip},
          {"typing", ImGui::GetIO().WantTextInput},
          {"active", ui::probe::active()},
          {"items", items},
          {"values", values}};
}

void write_probe_file(const fs::path& path, const nlohmann::json& probe) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) return;
    out << probe.dump() << '\n';
    if (!out) return;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
}

}  // namespace trispline::editor
