#include "ui/placement_panel.h"

#include "ui/theme.h"

#include <imgui.h>

#include <algorithm>

namespace trispline::ui {

const char* axis_name(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return names[std::clamp(axis, 0, 2)];
}

namespace {

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// Label in the left column, widget filling the rest of the row (Blender's property layout).
void row_label(const char* label) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(label);
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
}

}  // namespace

PlacementPanelResult draw_placement_panel(PlacementParams& p, std::string& object,
                                          const std::vector<std::string>& objects) {
  PlacementPanelResult r;
  auto done = [&] { r.committed |= ImGui::IsItemDeactivatedAfterEdit(); };

  row_label("Object");
  if (ImGui::BeginCombo("##object", object.empty() ? "(choose)" : object.c_str())) {
    for (const std::string& name : objects) {
      if (ImGui::Selectable(name.c_str(), name == object) && name != object) {
        object = name;
        r.object_changed = true;
      }
    }
    ImGui::EndCombo();
  }
  tooltip("The object to place along the stroke (defaults to the selected object)");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Volume");
  ImGui::Separator();
  row_label("Half-width");
  ImGui::DragScalar("##width", ImGuiDataType_Double, &p.width, 0.002f, nullptr, nullptr, "%.3f");
  done();
  tooltip("d: half-width of the band around the stroke (C(u) +- d N(u)), world units");
  p.width = std::max(p.width, 1e-4);
  row_label("Height");
  ImGui::DragScalar("##height", ImGuiDataType_Double, &p.height, 0.002f, nullptr, nullptr, "%.3f");
  done();
  tooltip("h: height of the deformation volume above the contact surface, world units");
  p.height = std::max(p.height, 1e-4);
  row_label("Type");
  int volume = p.offset_volume ? 1 : 0;
  if (ImGui::Combo("##volume", &volume, "extrude\0offset\0")) {
    p.offset_volume = volume == 1;
    r.committed = true;
  }
  tooltip(
      "extrude: layers along the view direction (Eq. 2.3)\n"
      "offset: layers along the contact surface normals (Eq. 2.4)");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Contact sampling");
  ImGui::Separator();
  row_label("Rays u x v");
  ImGui::DragInt2("##samples", p.samples, 0.2f, 2, 512);
  done();
  tooltip("nu x nv rays shot along the view direction through the band; more rays follow the surface closer");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Lattice");
  ImGui::Separator();
  row_label("Order u v w");
  ImGui::DragInt3("##order", p.order, 0.05f, 2, 6);
  done();
  tooltip("B-spline order per axis (degree + 1): 2 linear, 3 quadratic, 4 cubic");
  row_label("Controls");
  ImGui::DragInt3("##controls", p.controls, 0.1f, 2, 64);
  done();
  tooltip("Control points per axis (u along the stroke, v across, w up); at least the order");
  for (int a = 0; a < 3; ++a) {
    p.order[a] = std::clamp(p.order[a], 2, 6);
    p.controls[a] = std::clamp(p.controls[a], p.order[a], 64);
  }
  // The contact grid must have at least as many samples as control points along u and v.
  for (int a = 0; a < 2; ++a) p.samples[a] = std::clamp(p.samples[a], std::max(2, p.controls[a]), 512);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Object axes");
  ImGui::Separator();
  row_label("Length axis");
  if (ImGui::Combo("##length_axis", &p.length_axis, "x\0y\0z\0")) r.committed = true;
  tooltip("Object axis laid along the stroke (u)");
  row_label("Up axis");
  if (ImGui::Combo("##up_axis", &p.up_axis, "x\0y\0z\0")) r.committed = true;
  tooltip("Object axis pointing away from the surface (w); its minimum sits on the contact surface");
  if (p.up_axis == p.length_axis) ImGui::TextColored(colors::warning, "Length and up axes must differ.");

  ImGui::Spacing();
  if (ImGui::Button("Defaults")) {
    p = PlacementParams{};
    r.reset = r.committed = true;
  }
  tooltip("Reset every parameter to its default");
  return r;
}

}  // namespace trispline::ui
