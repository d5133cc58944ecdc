#include "ui/inside_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

#include "core/commands/object_inside.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

nlohmann::json inside_line(const std::string& object, const InsidePanelState& s, bool remove) {
  core::ObjectInsideParams p;
  p.object = object;
  p.color = s.color;
  p.texture_size = s.texture_size;
  if (remove)
    p.no_texture = true;
  else
    p.texture = s.texture;
  return core::ObjectInsideCommand::schema().to_json(p);
}

std::optional<nlohmann::json> draw_inside_panel(InsidePanelState& s, const core::SceneObject* object) {
  const auto& schema = core::ObjectInsideCommand::schema();
  ImGui::TextColored(colors::dim, "Inside");
  ImGui::Separator();
  if (!object) {
    ImGui::TextColored(colors::dim, "(select an object)");
    return std::nullopt;
  }
  if (s.synced_object != object->name) {
    s.synced_object = object->name;
    s.color = object->inside_color;
    s.texture.clear();
    s.texture_size = object->inside_texture_size;
  }
  std::optional<nlohmann::json> line;
  row_label("Colour");
  float rgb[3] = {s.color.x, s.color.y, s.color.z};
  if (ImGui::ColorEdit3("##inside_color", rgb, ImGuiColorEditFlags_Float)) s.color = {rgb[0], rgb[1], rgb[2]};
  probe::item("inside.color");
  tooltip(param_tooltip(schema.find("color")->doc).c_str());

  const std::string current = object->inside_texture ? object->inside_texture->uri : std::string();
  probe::value("inside.current", current);
  row_label("Texture");
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##inside_texture", current.empty() ? "image file (PNG, JPEG, EXR...)" : current.c_str(),
                           &s.texture);
  probe::item("inside.texture");
  probe::value("inside.texture", s.texture);
  tooltip((param_tooltip(schema.find("texture")->doc) + "\nEmpty: keep the current texture" +
           (current.empty() ? std::string(" (none)") : " (" + current + ")"))
              .c_str());
  row_label("Size");
  const double min_size = 1e-4, max_size = 1e6;
  if (drag_scalar("##inside_size", ImGuiDataType_Double, &s.texture_size, float(std::max(s.texture_size, 0.01) * 0.01),
                  &min_size, &max_size, "%.4g"))
    s.texture_size = std::clamp(s.texture_size, min_size, max_size);
  probe::item("inside.texture_size");
  tooltip(param_tooltip(schema.find("texture_size")->doc).c_str());
  if (!object->dffd)
    ImGui::TextColored(colors::dim, "The texture shows on DFFD caps: split the object with openings cap.");

  const float w = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
  if (ImGui::Button("Apply##inside", ImVec2(w, 0))) line = inside_line(object->name, s, false);
  probe::item("inside.apply");
  tooltip("Set the inside colour, texture and size (one undoable object.inside)");
  ImGui::SameLine();
  ImGui::BeginDisabled(!object->inside_texture);
  if (ImGui::Button("No texture##inside", ImVec2(w, 0))) line = inside_line(object->name, s, true);
  ImGui::EndDisabled();
  probe::item("inside.no_texture");
  tooltip("Remove the texture: the cut surfaces in the inside colour alone");
  if (line) s.texture.clear();
  return line;
}

}  // namespace trispline::ui
