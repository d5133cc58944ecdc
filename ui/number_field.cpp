#include "ui/number_field.h"

#include <imgui_internal.h>

namespace trispline::ui {

namespace {
ImGuiID g_pressed = 0;  // the drag field a mouse press activated (its text mode is not on)
}  // namespace

void click_to_type() {
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiID id = ImGui::GetItemID();
  if (id == 0) return;
  if (ImGui::IsItemActivated() && !ImGui::TempInputIsActive(id) && g.ActiveIdSource == ImGuiInputSource_Mouse)
    g_pressed = id;
  if (g_pressed != id || !ImGui::IsItemDeactivated()) return;
  g_pressed = 0;
  const float slop = g.IO.MouseDragThreshold;
  if (!ImGui::IsItemDeactivatedAfterEdit() && g.IO.MouseDragMaxDistanceSqr[0] < slop * slop)
    ImGui::SetKeyboardFocusHere(-1);  // ImGui: a drag field focused from code opens its text input
}

bool drag_scalar(const char* label, ImGuiDataType type, void* data, float speed, const void* min, const void* max,
                 const char* format, ImGuiSliderFlags flags) {
  const bool changed = ImGui::DragScalar(label, type, data, speed, min, max, format, flags);
  click_to_type();
  return changed;
}

bool drag_int(const char* label, int* v, float speed, int min, int max, const char* format, ImGuiSliderFlags flags) {
  return drag_scalar(label, ImGuiDataType_S32, v, speed, &min, &max, format, flags);
}

bool drag_scalar_n(const char* label, ImGuiDataType type, void* data, int components, float speed, const void* min,
                   const void* max, const char* format, ImGuiSliderFlags flags) {
  // ImGui::DragScalarN's layout, with each component a drag_scalar.
  if (ImGui::GetCurrentWindow()->SkipItems) return false;
  const ImGuiStyle& style = ImGui::GetStyle();
  const std::size_t size = ImGui::DataTypeGetInfo(type)->Size;
  bool changed = false;
  ImGui::BeginGroup();
  ImGui::PushID(label);
  ImGui::PushMultiItemsWidths(components, ImGui::CalcItemWidth());
  for (int i = 0; i < components; ++i) {
    ImGui::PushID(i);
    if (i > 0) ImGui::SameLine(0, style.ItemInnerSpacing.x);
    changed |= drag_scalar("", type, static_cast<char*>(data) + i * size, speed, min, max, format, flags);
    ImGui::PopID();
    ImGui::PopItemWidth();
  }
  ImGui::PopID();
  const char* label_end = ImGui::FindRenderedTextEnd(label);
  if (label != label_end) {
    ImGui::SameLine(0, style.ItemInnerSpacing.x);
    ImGui::TextEx(label, label_end);
  }
  ImGui::EndGroup();
  return changed;
}

bool drag_int_n(const char* label, int* v, int components, float speed, int min, int max, const char* format,
                ImGuiSliderFlags flags) {
  return drag_scalar_n(label, ImGuiDataType_S32, v, components, speed, &min, &max, format, flags);
}

}  // namespace trispline::ui
