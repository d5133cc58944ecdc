#include "ui/scene_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "ui/gui_probe.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

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

// A small camera (in renders) or the same camera struck through (out of renders); returns true when clicked.
bool camera_button(const char* id, bool rendered) {
  const float h = ImGui::GetFrameHeight();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const bool clicked = ImGui::InvisibleButton(id, ImVec2(h, h));
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const bool hovered = ImGui::IsItemHovered();
  const ImU32 col = ImGui::GetColorU32(hovered || rendered ? ImGuiCol_Text : ImGuiCol_TextDisabled,
                                       rendered && !hovered ? 0.6f : 1.0f);
  const ImVec2 c(p.x + h * 0.5f, p.y + h * 0.5f);
  const float w = h * 0.30f, t = h * 0.18f;  // body half-width and half-height
  dl->AddRect(ImVec2(c.x - w, c.y - t + 1.0f), ImVec2(c.x + w, c.y + t + 1.0f), col, 2.0f, 0, 1.5f);
  dl->AddRectFilled(ImVec2(c.x - w * 0.4f, c.y - t - 2.0f), ImVec2(c.x + w * 0.2f, c.y - t + 1.0f), col);
  dl->AddCircle(ImVec2(c.x, c.y + 1.0f), t * 0.6f, col, 10, 1.5f);
  if (!rendered) dl->AddLine(ImVec2(c.x - w, c.y + t + 2.0f), ImVec2(c.x + w, c.y - t - 2.0f), col, 1.5f);
  return clicked;
}

// The eye and camera cells of a row (object or volume `name`): a click requests object.visibility with that flag
// flipped. Returns true when one of them is hovered (the row's own tooltip is then not shown).
bool draw_visibility_cells(const std::string& name, bool visible, bool rendered, SceneRequest& req) {
  ImGui::TableNextColumn();
  if (eye_button("##eye", visible)) req = {SceneRequest::Kind::ToggleVisible, name};
  probe::item("scene.eye." + name);
  bool hovered = ImGui::IsItemHovered();
  if (hovered)
    ImGui::SetTooltip(visible ? "Hide in viewport (object.visibility viewport false)\n"
                                "Still recorded and exported unless its camera is off"
                              : "Show in viewport (object.visibility viewport true)");
  ImGui::TableNextColumn();
  if (camera_button("##render", rendered)) req = {SceneRequest::Kind::ToggleRender, name};
  probe::item("scene.render." + name);
  if (ImGui::IsItemHovered()) {
    hovered = true;
    ImGui::SetTooltip(rendered ? "Leave out of renders (object.visibility render false): recordings, animation.glb,\n"
                                 "scene.glb and farm frames skip it; a volume then costs nothing there"
                               : "Include in renders (object.visibility render true)");
  }
  return hovered;
}

// Object colours are linear RGB; ImGui draws sRGB-ish values.
ImVec4 to_display(const glm::vec3& c) {
  auto g = [](float v) { return std::pow(std::clamp(v, 0.0f, 1.0f), 1.0f / 2.2f); };
  return ImVec4(g(c.x), g(c.y), g(c.z), 1.0f);
}

// Location / Rotation / Scale of `o` as typed fields (a click enters text). Values come from the scene unless a field
// is being edited; leaving an edited row requests object.transform with that row.
void draw_transform_fields(const core::SceneObject& o, TransformFields& f, SceneRequest& req) {
  if (f.object != o.name || !(f.active || f.dirty)) {
    f.object = o.name;
    f.dirty = false;
    const glm::dvec3 v[3] = {o.transform.translate, o.transform.rotate_deg, o.transform.scale};
    for (int r = 0; r < 3; ++r)
      for (int a = 0; a < 3; ++a) f.values[r][a] = v[r][a];
  }
  ImGui::Separator();
  ImGui::TextColored(colors::dim, "Transform");
  static const char* kLabels[] = {"Location", "Rotation", "Scale"};
  static const char* kFields[] = {"translate", "rotate_deg", "scale"};
  static const char* kTips[] = {"world units (x, y, z)", "degrees about x, then y, then z", "per axis, > 0"};
  const float label_w = ImGui::CalcTextSize("Location").x + ImGui::GetStyle().ItemSpacing.x * 2;
  bool active = false;
  for (int r = 0; r < 3; ++r) {
    ImGui::PushID(r);
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(kLabels[r]);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kTips[r]);
    ImGui::SameLine(label_w);
    ImGui::SetNextItemWidth(-FLT_MIN);
    if (ImGui::InputScalarN("##xyz", ImGuiDataType_Double, f.values[r], 3, nullptr, nullptr, r == 1 ? "%.2f" : "%.3f"))
      f.dirty = true;
    probe::item(std::string("scene.transform.") + kFields[r]);  // the row (x, y, z fields side by side)
    f.row_min[r] = {ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y};
    f.row_max[r] = {ImGui::GetItemRectMax().x, ImGui::GetItemRectMax().y};
    active = active || ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      req = {SceneRequest::Kind::Transform, o.name, kFields[r],
             glm::dvec3(f.values[r][0], f.values[r][1], f.values[r][2])};
      f.dirty = false;
    }
    ImGui::PopID();
  }
  f.active = active;
}

// A volume's row: eye, swatch, name (select / double-click frames), and "volume" where meshes show vertices.
void draw_volume_row(const core::VolumeObject& v, const ScenePanelState& state, SceneRequest& req) {
  ImGui::PushID(("volume:" + v.name).c_str());
  ImGui::TableNextRow();
  const bool visible = v.visible;
  const bool eye_hovered = draw_visibility_cells(v.name, v.visible, v.render_visible, req);
  ImGui::TableNextColumn();
  ImGui::ColorButton("##swatch", to_display(v.color), ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop,
                     ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
  ImGui::SameLine();
  if (!visible) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  if (ImGui::Selectable(v.name.c_str(), v.name == state.selected,
                        ImGuiSelectableFlags_SpanAllColumns | ImGuiSelectableFlags_AllowItemOverlap |
                            ImGuiSelectableFlags_AllowDoubleClick))
    req = {ImGui::IsMouseDoubleClicked(0) ? SceneRequest::Kind::Frame : SceneRequest::Kind::Select, v.name};
  probe::item("scene.object." + v.name);
  if (!visible) ImGui::PopStyleColor();
  if (ImGui::IsItemHovered() && !eye_hovered) {
    const auto& d = v.spline->dims();
    ImGui::SetTooltip("%s (volume, %d x %d x %d samples)\nsource: %s\niso-level %g %s\ndouble-click to frame",
                      v.name.c_str(), d[0], d[1], d[2], v.source.c_str(), v.iso, v.units.c_str());
  }
  ImGui::TableNextColumn();
  ImGui::TextColored(colors::dim, "volume");
  ImGui::PopID();
}

constexpr const char* kTextDialog = "Add text";

// The Add ▸ Text… dialog: the text, its size and depth (scene.text's declared fields). True when Add was pressed.
bool draw_text_dialog(core::SceneTextParams& p) {
  bool add = false;
  if (!ImGui::BeginPopupModal(kTextDialog, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return false;
  const auto& schema = core::SceneTextCommand::schema();
  row_label("Text");
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  ImGui::SetNextItemWidth(280);
  ImGui::InputText("##text", &p.text);
  const bool entered = ImGui::IsItemDeactivated() && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter), false);
  probe::item("scene.text.text");
  if (ImGui::IsItemHovered()) tooltip(param_tooltip(schema.find("text")->doc).c_str());
  param_widget(schema, "size", p);
  param_widget(schema, "depth", p);
  ImGui::Spacing();
  ImGui::BeginDisabled(p.text.empty());
  add = ImGui::Button("Add", ImVec2(120, 0)) || (entered && !p.text.empty());
  probe::item("scene.text.add");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    ImGui::CloseCurrentPopup();
  if (add) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return add;
}

}  // namespace

SceneRequest draw_scene_panel(const Rect& rect, const core::Scene& scene, const ScenePanelState& state) {
  SceneRequest req;
  if (begin_docked("Scene", rect)) {
    if (ImGui::Button("Load...")) req.kind = SceneRequest::Kind::Load;
    probe::item("scene.load");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "Load a mesh (OBJ, PLY, OFF, STL, glTF, GLB) as a new object, or a CT/MRI volume (NIfTI .nii /\n"
          ".nii.gz, a DICOM series folder or .dcm file, an InVesalius .inv3 project) as a trivariate\n"
          "B-spline whose iso-surface and silhouettes are drawn");
    ImGui::SameLine();
    if (ImGui::Button("Add")) ImGui::OpenPopup("##add_primitive");
    probe::item("scene.add");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add a primitive (scene.primitive) or a line of text (scene.text)");
    bool open_text = false;
    if (ImGui::BeginPopup("##add_primitive")) {
      for (const char* kind : kPrimitiveKinds)
        if (ImGui::MenuItem(kind)) req = {SceneRequest::Kind::AddPrimitive, kind};
      if (state.text) {
        ImGui::Separator();
        open_text = ImGui::MenuItem("Text...");
        probe::item("scene.add.text");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("A line of text as an extruded mesh (scene.text)");
      }
      ImGui::EndPopup();
    }
    if (open_text) ImGui::OpenPopup(kTextDialog);
    if (state.text && draw_text_dialog(*state.text)) req.kind = SceneRequest::Kind::AddText;
    ImGui::SameLine();
    ImGui::BeginDisabled(state.selected.empty() || !state.can_remove || !scene.find(state.selected));
    if (ImGui::Button("Remove")) req = {SceneRequest::Kind::Remove, state.selected};
    ImGui::EndDisabled();
    ImGui::Separator();
    if (scene.objects().empty() && scene.volumes().empty())
      ImGui::TextColored(colors::dim, "Empty scene: Load... or Add a primitive.");

    const core::SceneObject* sel = scene.find(state.selected);
    const bool show_transform = sel && state.transform;
    const ImGuiStyle& style = ImGui::GetStyle();
    const float reserve = show_transform ? 4 * ImGui::GetFrameHeightWithSpacing() + style.ItemSpacing.y : 0.0f;
    const int flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
    if (ImGui::BeginTable("##objects", 4, flags, ImVec2(0.0f, -reserve))) {
      ImGui::TableSetupColumn("##eye", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFrameHeight());
      ImGui::TableSetupColumn("##render", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFrameHeight());
      ImGui::TableSetupColumn("Object", ImGuiTableColumnFlags_WidthStretch);
      ImGui::TableSetupColumn("Vertices", ImGuiTableColumnFlags_WidthFixed, 70.0f);
      for (const core::SceneObject& o : scene.objects()) {
        ImGui::PushID(o.name.c_str());
        ImGui::TableNextRow();
        const bool visible = o.visible;
        const bool eye_hovered = draw_visibility_cells(o.name, o.visible, o.render_visible, req);
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
      for (const core::VolumeObject& v : scene.volumes()) draw_volume_row(v, state, req);
      ImGui::EndTable();
    }
    if (show_transform) draw_transform_fields(*sel, *state.transform, req);
  }
  ImGui::End();
  return req;
}

}  // namespace trispline::ui
