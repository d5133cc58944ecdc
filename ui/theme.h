// trispline::ui theme — a dark, low-contrast style close to Blender's default theme, and the few accent colours
// the panels share (errors, warnings, selection).
#pragma once

#include <imgui.h>

#include <cstdio>
#include <string>

namespace trispline::ui {

void apply_dark_theme(float scale = 1.0f);  // sets ImGui::GetStyle() colours, rounding and spacing

namespace colors {
inline const ImVec4 error{1.00f, 0.42f, 0.40f, 1.0f};
inline const ImVec4 warning{1.00f, 0.78f, 0.35f, 1.0f};
inline const ImVec4 dim{0.60f, 0.60f, 0.62f, 1.0f};
inline const ImVec4 accent{0.33f, 0.56f, 0.89f, 1.0f};  // Blender's selection blue
// The frame of a field whose typed value was limited (its tooltip says why): amber, dark enough for white text.
inline const ImVec4 limited_frame{0.52f, 0.36f, 0.06f, 1.0f};
}  // namespace colors

// Around a field whose typed value was limited: its frame amber whether idle, hovered or being edited.
inline void push_limited_frame() {
  ImGui::PushStyleColor(ImGuiCol_FrameBg, colors::limited_frame);
  ImGui::PushStyleColor(ImGuiCol_FrameBgHovered, colors::limited_frame);
  ImGui::PushStyleColor(ImGuiCol_FrameBgActive, colors::limited_frame);
}
inline void pop_limited_frame() { ImGui::PopStyleColor(3); }

// A number as a person types it: %.6g ("1.5", "0.07", "1e-05").
inline std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace trispline::ui
