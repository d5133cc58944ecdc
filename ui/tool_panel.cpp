#include "ui/tool_panel.h"

#include <imgui.h>

#include <algorithm>

#include "core/commands/lattice_set_point.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/theme.h"

namespace trispline::ui {

bool begin_tool_panel(const Rect& rect, const std::vector<ToolEntry>& tools, int* active) {
  if (!begin_docked("Tool", rect)) return false;
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  probe::rect("panel.tool", pos, ImVec2(pos.x + size.x, pos.y + size.y));
  const float w = ImGui::GetContentRegionAvail().x;
  for (int i = 0; i < int(tools.size()); ++i) {
    const bool on = i == *active;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_HeaderActive));
    if (ImGui::Button(tools[i].name.c_str(), ImVec2(w, 0))) *active = i;
    probe::item("tool." + tools[i].name);
    if (on) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", tools[i].tooltip.c_str(), tools[i].shortcut.c_str());
  }
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::Spacing();
  return true;
}

void end_tool_panel() { ImGui::End(); }

nlohmann::json set_point_line(const std::string& object, const int index[3], const double position[3]) {
  return core::LatticeSetPointCommand::schema().to_json(
      core::LatticeSetPointParams{object, {index[0], index[1], index[2]}, {position[0], position[1], position[2]}});
}

std::optional<nlohmann::json> draw_control_point_section(const core::SceneObject& object, ControlPointState& st) {
  std::optional<nlohmann::json> line;
  if (!object.ffd) return line;
  if (st.object != object.name) {
    st = ControlPointState{};
    st.object = object.name;
  }
  st.highlight = false;
  ImGui::Spacing();
  if (!ImGui::CollapsingHeader("Control point", ImGuiTreeNodeFlags_DefaultOpen)) return line;
  const float top = ImGui::GetCursorScreenPos().y;
  const glm::ivec3 n = object.ffd->lattice.control_counts();
  static const char* axis[] = {"i (u)", "j (v)", "k (w)"};
  static const char* tips[] = {"Control point index along u (the stroke), 0 to %d",
                               "Control point index along v (across the stroke), 0 to %d",
                               "Control point index along w (0 = contact surface, up to the top), 0 to %d"};
  ImGui::PushID("control_point");
  for (int a = 0; a < 3; ++a) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(axis[a]);
    ImGui::SameLine(110.0f);
    ImGui::SetNextItemWidth(-1);
    ImGui::PushID(a);
    ImGui::InputInt("##index", &st.index[a], 1, 5);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip(tips[a], n[a] - 1);
    ImGui::PopID();
    st.index[a] = std::clamp(st.index[a], 0, n[a] - 1);
  }
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("Position");
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
  drag_scalar_n("##position", ImGuiDataType_Double, st.position, 3, 0.002f, nullptr, nullptr, "%.4f");
  const bool active = ImGui::IsItemActive();
  if (ImGui::IsItemDeactivatedAfterEdit()) line = set_point_line(object.name, st.index, st.position);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "World position of control point P_ijk, world units. Releasing the drag (or Enter) issues one\n"
        "lattice.set_point: undoable, logged. The object follows the lattice (FFD, seed Eq. 2.1)");
  if (!active && !line) {
    const glm::dvec3 p = object.ffd->lattice.control_point(st.index[0], st.index[1], st.index[2]);
    st.position[0] = p.x, st.position[1] = p.y, st.position[2] = p.z;
  }
  ImGui::TextColored(colors::dim, "%d x %d x %d control points", n.x, n.y, n.z);
  const ImVec2 m = ImGui::GetIO().MousePos;
  st.highlight = active || (ImGui::IsWindowHovered() && m.y >= top && m.y <= ImGui::GetCursorScreenPos().y);
  ImGui::PopID();
  return line;
}

}  // namespace trispline::ui
