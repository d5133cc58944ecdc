#include "ui/layout.h"

#include <algorithm>
#include <cmath>

namespace trispline::ui {

DockLayout compute_layout(ImVec2 display, float menu_h, float status_h, const LayoutSizes& sizes, bool show_tool,
                          bool show_right, bool show_log) {
  DockLayout l;
  const float top = menu_h;
  const float height = std::max(1.0f, display.y - menu_h - status_h);
  float left = show_tool ? sizes.left_width : 0.0f;
  float right = show_right ? sizes.right_width : 0.0f;
  const float max_sides = display.x * (2.0f / 3.0f);
  if (left + right > max_sides && left + right > 0) {
    const float k = max_sides / (left + right);
    left *= k;
    right *= k;
  }
  const float mid_w = std::max(1.0f, display.x - left - right);
  const float log_h = show_log ? std::min(sizes.log_height, height * 0.4f) : 0.0f;
  const float scene_h = std::floor(height * sizes.scene_fraction);

  l.tool = {{0, top}, {left, height}};
  l.scene = {{display.x - right, top}, {right, scene_h}};
  l.history = {{display.x - right, top + scene_h}, {right, height - scene_h}};
  l.log = {{left, top + height - log_h}, {mid_w, log_h}};
  l.viewport = {{left, top}, {mid_w, height - log_h}};
  return l;
}

bool begin_docked(const char* title, const Rect& r, int extra_flags) {
  ImGui::SetNextWindowPos(r.pos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(r.size, ImGuiCond_Always);
  return ImGui::Begin(title, nullptr, kDockedWindowFlags | extra_flags);
}

RectPair split_rect(const Rect& r, float top_fraction) {
  const float top = std::floor(r.size.y * std::clamp(top_fraction, 0.0f, 1.0f));
  return {{r.pos, {r.size.x, top}}, {{r.pos.x, r.pos.y + top}, {r.size.x, r.size.y - top}}};
}

}  // namespace trispline::ui
