// trispline::ui number fields — ImGui's drag fields that an artist can also type into at any frame rate.
// ImGui enters a drag field's text mode on Ctrl+click or a double-click; at the 2-4 fps of software GL a
// double-click never arrives (both clicks land in one frame, or in frames > 0.3 s apart). Here a click that does not
// drag enters text editing with the value selected (typing replaces it, Enter or a click elsewhere applies it), and
// a drag still changes the value. Same arguments and return values as the ImGui functions they wrap.
#pragma once

#include <imgui.h>

namespace trispline::ui {

// Call right after any ImGui drag widget: a click on it without a drag enters its text mode next frame.
void click_to_type();

bool drag_int(const char* label, int* v, float speed = 1.0f, int min = 0, int max = 0, const char* format = "%d",
              ImGuiSliderFlags flags = 0);
bool drag_int_n(const char* label, int* v, int components, float speed = 1.0f, int min = 0, int max = 0,
                const char* format = "%d", ImGuiSliderFlags flags = 0);
bool drag_scalar(const char* label, ImGuiDataType type, void* data, float speed, const void* min = nullptr,
                 const void* max = nullptr, const char* format = nullptr, ImGuiSliderFlags flags = 0);
bool drag_scalar_n(const char* label, ImGuiDataType type, void* data, int components, float speed,
                   const void* min = nullptr, const void* max = nullptr, const char* format = nullptr,
                   ImGuiSliderFlags flags = 0);

}  // namespace trispline::ui
