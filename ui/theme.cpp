#include "ui/theme.h"

namespace trispline::ui {

void apply_dark_theme(float scale) {
  ImGui::StyleColorsDark();
  ImGuiStyle& s = ImGui::GetStyle();
  s.WindowRounding = 4.0f;
  s.ChildRounding = 3.0f;
  s.FrameRounding = 3.0f;
  s.PopupRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.TabRounding = 3.0f;
  s.ScrollbarRounding = 6.0f;
  s.WindowBorderSize = 1.0f;
  s.FrameBorderSize = 0.0f;
  s.WindowPadding = ImVec2(8, 8);
  s.FramePadding = ImVec2(6, 3);
  s.ItemSpacing = ImVec2(6, 4);
  s.WindowTitleAlign = ImVec2(0.0f, 0.5f);
  s.ScrollbarSize = 12.0f;

  ImVec4* c = s.Colors;
  auto rgb = [](float r, float g, float b, float a = 1.0f) { return ImVec4(r, g, b, a); };
  c[ImGuiCol_Text] = rgb(0.90f, 0.90f, 0.90f);
  c[ImGuiCol_TextDisabled] = rgb(0.50f, 0.50f, 0.52f);
  c[ImGuiCol_WindowBg] = rgb(0.19f, 0.19f, 0.20f, 0.97f);
  c[ImGuiCol_ChildBg] = rgb(0.16f, 0.16f, 0.17f, 1.0f);
  c[ImGuiCol_PopupBg] = rgb(0.14f, 0.14f, 0.15f, 0.98f);
  c[ImGuiCol_Border] = rgb(0.10f, 0.10f, 0.10f, 1.0f);
  c[ImGuiCol_FrameBg] = rgb(0.11f, 0.11f, 0.12f);
  c[ImGuiCol_FrameBgHovered] = rgb(0.27f, 0.27f, 0.29f);
  c[ImGuiCol_FrameBgActive] = rgb(0.30f, 0.30f, 0.33f);
  c[ImGuiCol_TitleBg] = rgb(0.14f, 0.14f, 0.15f);
  c[ImGuiCol_TitleBgActive] = rgb(0.16f, 0.16f, 0.18f);
  c[ImGuiCol_TitleBgCollapsed] = rgb(0.14f, 0.14f, 0.15f);
  c[ImGuiCol_MenuBarBg] = rgb(0.14f, 0.14f, 0.15f);
  c[ImGuiCol_ScrollbarBg] = rgb(0.16f, 0.16f, 0.17f);
  c[ImGuiCol_CheckMark] = colors::accent;
  c[ImGuiCol_SliderGrab] = rgb(0.33f, 0.56f, 0.89f, 0.85f);
  c[ImGuiCol_SliderGrabActive] = colors::accent;
  c[ImGuiCol_Button] = rgb(0.30f, 0.30f, 0.32f);
  c[ImGuiCol_ButtonHovered] = rgb(0.38f, 0.38f, 0.41f);
  c[ImGuiCol_ButtonActive] = rgb(0.28f, 0.45f, 0.70f);
  c[ImGuiCol_Header] = rgb(0.28f, 0.45f, 0.70f, 0.55f);
  c[ImGuiCol_HeaderHovered] = rgb(0.33f, 0.50f, 0.78f, 0.70f);
  c[ImGuiCol_HeaderActive] = rgb(0.33f, 0.56f, 0.89f, 0.90f);
  c[ImGuiCol_Separator] = rgb(0.28f, 0.28f, 0.30f);
  c[ImGuiCol_Tab] = rgb(0.16f, 0.16f, 0.18f);
  c[ImGuiCol_TabHovered] = rgb(0.33f, 0.50f, 0.78f, 0.80f);
  c[ImGuiCol_TabActive] = rgb(0.24f, 0.24f, 0.27f);
  c[ImGuiCol_TableHeaderBg] = rgb(0.16f, 0.16f, 0.18f);
  c[ImGuiCol_TableRowBgAlt] = rgb(1.0f, 1.0f, 1.0f, 0.03f);
  c[ImGuiCol_ModalWindowDimBg] = rgb(0.0f, 0.0f, 0.0f, 0.45f);
  s.ScaleAllSizes(scale);
}

}  // namespace trispline::ui
