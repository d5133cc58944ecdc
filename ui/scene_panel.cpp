#include "ui/scene_panel.h"

#include "ui/gui_probe.h"
#include "ui/theme.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace trispline::ui {

namespace {

// A small eye (open) or a dash (hidden) drawn with the window draw list; returns true when clicked.
bool eye_button(const char* id, bool visible) {
  const float h = ImGui::GetFrameHeight();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const bool clicked = ImGui::InvisibleButton(id, ImVec2(h, h));
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImU32 col = ImGui::GetColorU32(ImGui::IsItemHovered() ? ImGuiCol_Text : ImGuiCol_TextDisabled);
  const ImVec2 c(p.x + h * 0.5f, p.y + h * 0.5f);
  if (visible) {
    const float rx = h * 0.34f, ry = h * 0.2f;
    dl->PathArcTo(ImVec2(c.x, c.y + ry), rx * 1.2f, 3.14159f * 1.18f, 3.14159f * 1.82f, 10);
    dl->PathArcTo(ImVec2(c.x, c.y - ry), rx * 1.2f, 3.14159f * 0.18f, 3.14159f * 0.82f, 10);
    dl->PathStroke(col, ImDrawFlags_Closed, 1.5f);
    dl->AddCircleFilled(c, h * 0.12f, col);
  } else {
    dl->AddLine(ImVec2(c.x - h * 0.3f, c.y), ImVec2(c.x + h * 0.3f, c.y), col, 1.5f);
  }
  return clicked;
}

// Object colours are linear RGB; ImGui draws sRGB-ish values.
ImVec4 to_display(const glm::vec3& c) {
  auto g = [](float v) { return std::pow(std::clamp(v, 0.0f, 1.0f), 1.0f / 2.2f); };
  return ImVec4(g(c.x), g(c.y), g(c.z), 1.0f);
}

}  // namespace

SceneRequest draw_scene_panel(const Rect& rect, const core::Scene& scene, const ScenePanelState& state) {
  SceneRequest req;
  if (begin_docked("Scene", rect)) {
    if (ImGui::Button("Load...")) req.kind = SceneRequest::Kind::Load;
    probe::item("scene.load");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Load a mesh (OBJ, PLY, OFF, STL, glTF, GLB) as a new object");
    ImGui::SameLine();
    if (ImGui::Button("Add")) ImGui::OpenPopup("##add_primitive");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add a primitive (scene.primitive)");
    if (ImGui::BeginPopup("##add_primitive")) {
      for (const char* kind : kPrimitiveKinds)
        if (ImGui::MenuItem(kind)) req = {SceneRequest::Kind::AddPrimitive, kind};
      ImGui::EndPopup();
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(state.selected.empty() || !state.can_remove || !scene.find(state.selected));
    if (ImGui::Button("Remove")) req = {SceneRequest::Kind::Remove, state.selected};
    ImGui::EndDisabled();
    ImGui::Separator();
    if (scene.objects().empty()) ImGui::TextColored(colors::dim, "Empty scene: Load... or Add a primitive.");

    const int flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
    if (ImGui::BeginTable("##objects", 3, flags)) {
      ImGui::TableSetupColumn("##eye", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFrameHeight());
      ImGui::TableSetupColumn("Object", ImGuiTableColumnFlags_WidthStretch);
      ImGui::TableSetupColumn("Vertices", ImGuiTableColumnFlags_WidthFixed, 70.0f);
      for (const core::SceneObject& o : scene.objects()) {
        ImGui::PushID(o.name.c_str());
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        const bool visible = o.visible && !state.hidden.count(o.name);
        if (eye_button("##eye", visible)) req = {SceneRequest::Kind::ToggleVisible, o.name};
        const bool eye_hovered = ImGui::IsItemHovered();
        if (eye_hovered) ImGui::SetTooltip(visible ? "Hide in viewport" : "Show in viewport");
        ImGui::TableNextColumn();
        ImGui::ColorButton("##swatch", to_display(o.color),
                           ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop,
                           ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
        ImGui::SameLine();
        const bool selected = o.name == state.selected;
        if (!visible) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        if (ImGui::Selectable(o.name.c_str(), selected,
                              ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap |
                                  ImGuiSelectableFlags_AllowDoubleClick)) {
          req = {ImGui::IsMouseDoubleClicked(0) ? SceneRequest::Kind::Frame : SceneRequest::Kind::Select, o.name};
        }
        probe::item("scene.object." + o.name);
        if (!visible) ImGui::PopStyleColor();
        if (ImGui::IsItemHovered() && !eye_hovered) {
          ImGui::SetTooltip("%s\nsource: %s%s\ndouble-click to frame", o.name.c_str(), o.source.c_str(),
                            o.ffd ? "\ndeformed (FFD lattice)" : "");
        }
        ImGui::TableNextColumn();
        const std::size_t verts = o.world_mesh ? o.world_mesh->vertex_count() : 0;
        ImGui::TextColored(colors::dim, "%zu", verts);
        ImGui::PopID();
      }
      ImGui::EndTable();
    }
  }
  ImGui::End();
  return req;
}

}  // namespace trispline::ui
