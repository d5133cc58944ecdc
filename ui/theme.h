// trispline::ui theme — a dark, low-contrast style close to Blender's default theme, and the few accent colours
// the panels share (errors, warnings, selection).
#pragma once

#include <imgui.h>

namespace trispline::ui {

void apply_dark_theme(float scale = 1.0f);  // sets ImGui::GetStyle() colours, rounding and spacing

namespace colors {
inline const ImVec4 error{1.00f, 0.42f, 0.40f, 1.0f};
inline const ImVec4 warning{1.00f, 0.78f, 0.35f, 1.0f};
inline const ImVec4 dim{0.60f, 0.60f, 0.62f, 1.0f};
inline const ImVec4 accent{0.33f, 0.56f, 0.89f, 1.0f};  // Blender's selection blue
}  // namespace colors

}  // namespace trispline::ui
