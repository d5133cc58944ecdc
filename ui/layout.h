// trispline::ui layout — Blender-like docking of the fixed panels around the 3-D viewport, recomputed from the
// window size every frame (ImGui 1.86 has no docking branch):
//
//   +-------------------- main menu bar --------------------+
//   | Tool      |        viewport (free area)   | Scene     |
//   |           |                               |-----------|
//   |           |-------------------------------| History   |
//   |           | Log                           |           |
//   +---------------------- status bar ---------------------+
//
// The viewport itself is the whole window (the renderer draws behind the panels); `viewport` is the free part.
#pragma once

#include <imgui.h>

namespace trispline::ui {

struct Rect {
  ImVec2 pos{0, 0};   // pixels, top-left origin
  ImVec2 size{0, 0};  // pixels
  bool contains(ImVec2 p) const { return p.x >= pos.x && p.y >= pos.y && p.x < pos.x + size.x && p.y < pos.y + size.y; }
};

struct LayoutSizes {
  float left_width = 300;       // Tool column
  float right_width = 330;      // Scene / History column
  float log_height = 170;       // Log strip under the viewport
  float scene_fraction = 0.5f;  // share of the right column given to Scene
};

struct DockLayout {
  Rect tool, scene, history, log;
  Rect viewport;  // the part of the window not covered by panels
};

// display: window size in pixels; menu_h / status_h: heights of the menu bar and status bar.
// Columns shrink proportionally on small windows so the viewport keeps at least a third of the width.
DockLayout compute_layout(ImVec2 display, float menu_h, float status_h, const LayoutSizes& sizes = {},
                          bool show_tool = true, bool show_right = true, bool show_log = true);

// `r` cut horizontally: the top `top_fraction` of its height, then the rest (a column holding two panels).
struct RectPair {
  Rect top, bottom;
};
RectPair split_rect(const Rect& r, float top_fraction);

// Flags for a docked panel window (fixed position/size, no saved settings).
constexpr int kDockedWindowFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;

// SetNextWindowPos/Size to `r` and Begin(title) with kDockedWindowFlags | extra. Always pair with ImGui::End().
bool begin_docked(const char* title, const Rect& r, int extra_flags = 0);

}  // namespace trispline::ui
