#include "editor/session/navigation.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace trispline::editor {

namespace {
constexpr double kOrbitDegPerPx = 0.4;
constexpr double kZoomStep = 0.85;  // distance factor per wheel step
constexpr double kMaxPitch = 89.5;
}  // namespace

NavInput nav_input_from_imgui() {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::dvec2 scale(io.DisplayFramebufferScale.x, io.DisplayFramebufferScale.y);
  NavInput in;
  in.mouse_px = glm::dvec2(io.MousePos.x, io.MousePos.y) * scale;
  if (ImGui::IsMousePosValid() && io.MouseDelta.x > -1e5f)
    in.delta_px = glm::dvec2(io.MouseDelta.x, io.MouseDelta.y) * scale;
  in.wheel = io.MouseWheel;
  in.left_down = io.MouseDown[0];
  in.left_pressed = io.MouseClicked[0];
  in.middle_down = io.MouseDown[2];
  in.middle_pressed = io.MouseClicked[2];
  in.shift = io.KeyShift;
  in.alt = io.KeyAlt;
  in.ctrl = io.KeyCtrl;
  return in;
}

void Navigator::set_from_camera(const core::Camera& c) {
  pivot_ = c.target;
  const glm::dvec3 d = c.eye - c.target;
  distance_ = std::max(glm::length(d), 1e-6);
  pitch_deg_ = glm::degrees(std::asin(std::clamp(d.y / distance_, -1.0, 1.0)));
  pitch_deg_ = std::clamp(pitch_deg_, -kMaxPitch, kMaxPitch);
  yaw_deg_ = glm::degrees(std::atan2(d.x, d.z));
  fov_deg_ = c.fov_deg;
}

void Navigator::follow(const core::Camera& c, bool camera_set, glm::ivec2 viewport) {
  const core::Camera& f = followed_;
  if (camera_set &&
      (!followed_set_ || c.eye != f.eye || c.target != f.target || c.up != f.up || c.fov_deg != f.fov_deg))
    adopt(c, viewport);
  followed_ = c;
  followed_set_ = camera_set;
}

void Navigator::adopt(const core::Camera& c, glm::ivec2 viewport) {
  set_from_camera(c);
  followed_ = c;
  followed_set_ = true;
  if (c.viewport == viewport) return;  // saved from a window of this size: show exactly what was saved
  const glm::dvec2 v = visible_fraction(viewport);
  const double aspect = double(std::max(viewport.x, 1)) / double(std::max(viewport.y, 1));
  distance_ *= std::max({1.0, 1.0 / v.y, c.aspect() / (aspect * v.x)});
}

glm::dvec3 Navigator::eye() const {
  const double yaw = glm::radians(yaw_deg_), pitch = glm::radians(pitch_deg_);
  const glm::dvec3 dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  return pivot_ + distance_ * dir;
}

core::Camera Navigator::camera(glm::ivec2 viewport) const {
  core::Camera c;
  c.eye = eye();
  c.target = pivot_;
  c.up = {0.0, 1.0, 0.0};
  c.fov_deg = fov_deg_;
  c.viewport = glm::max(viewport, glm::ivec2(1));
  c.near_plane = std::max(1e-4, distance_ * 1e-3);
  c.far_plane = std::max(1000.0, distance_ * 100.0);
  return c;
}

void Navigator::orbit(glm::dvec2 delta_px) {
  yaw_deg_ = std::fmod(yaw_deg_ - delta_px.x * kOrbitDegPerPx, 360.0);
  pitch_deg_ = std::clamp(pitch_deg_ + delta_px.y * kOrbitDegPerPx, -kMaxPitch, kMaxPitch);
}

void Navigator::pan(glm::dvec2 delta_px, glm::ivec2 viewport) {
  const core::Camera c = camera(viewport);
  const double units_per_px = 2.0 * distance_ * std::tan(glm::radians(fov_deg_) * 0.5) / double(c.viewport.y);
  pivot_ += (-delta_px.x * c.right() + delta_px.y * c.true_up()) * units_per_px;
}

void Navigator::zoom(double steps, glm::dvec2 cursor_px, glm::ivec2 viewport) {
  if (steps == 0) return;
  const core::Camera c = camera(viewport);
  const double factor = std::pow(kZoomStep, steps);
  // The point under the cursor on the plane through the pivot facing the camera stays under the cursor.
  const glm::dvec3 dir = c.ray_direction(cursor_px);
  const double along = glm::dot(dir, c.forward());
  if (along > 1e-6) {
    const glm::dvec3 under_cursor = c.eye + dir * (distance_ / along);
    pivot_ += (under_cursor - pivot_) * (1.0 - factor);
  }
  distance_ = std::clamp(distance_ * factor, 1e-4, 1e6);
}

void Navigator::frame(const core::Aabb& box, glm::ivec2 viewport) {
  if (!box.valid()) return;
  const glm::dvec2 size = glm::max(glm::dvec2(viewport), glm::dvec2(1.0));
  const glm::dvec2 lo = glm::clamp(visible_lo_, glm::dvec2(0.0), size);
  const glm::dvec2 hi = glm::clamp(visible_hi_, lo + 1.0, glm::max(size, lo + 1.0));
  // Fit the bounding sphere into the visible rectangle's half extents...
  const glm::dvec2 v = glm::max(0.5 * (hi - lo), glm::dvec2(16.0)) / (0.5 * size);
  const double radius = std::max(0.5 * box.diagonal(), 1e-3);
  const double aspect = size.x / size.y;
  const double tan_v = std::tan(glm::radians(fov_deg_) * 0.5);
  const double tan_fit = std::min(tan_v * v.y, tan_v * aspect * v.x);
  distance_ = 1.1 * radius / std::sin(std::atan(tan_fit));
  // ...and centre it there rather than at the window's centre: the pivot moves in the view plane by the offset of
  // the visible centre from the window centre (so orbiting turns about that point, a little beside the box centre).
  pivot_ = box.center();
  const core::Camera c = camera(viewport);
  const double units_per_px = 2.0 * distance_ * tan_v / size.y;
  const glm::dvec2 shift = 0.5 * (lo + hi) - 0.5 * size;  // pixels, x right, y down
  pivot_ -= (shift.x * c.right() - shift.y * c.true_up()) * units_per_px;
}

glm::dvec2 Navigator::visible_fraction(glm::ivec2 viewport) const {
  const glm::dvec2 size = glm::max(glm::dvec2(viewport), glm::dvec2(1.0)), centre = 0.5 * size;
  // Half extents (pixels) around the view centre that stay visible between the panels.
  const glm::dvec2 lo = glm::clamp(visible_lo_, glm::dvec2(0.0), centre);
  const glm::dvec2 hi = glm::clamp(visible_hi_, centre, size);
  return glm::max(glm::min(centre - lo, hi - centre), glm::dvec2(16.0)) / centre;
}

bool Navigator::update(const NavInput& in, glm::ivec2 viewport) {
  if (in.left_pressed && in.alt) alt_drag_ = true;
  if (!in.left_down) alt_drag_ = false;

  const bool dragging = in.middle_down || alt_drag_;
  if (dragging && (in.delta_px.x != 0 || in.delta_px.y != 0)) {
    if (in.shift)
      pan(in.delta_px, viewport);
    else if (in.ctrl)
      zoom(-in.delta_px.y * 0.05, in.mouse_px, viewport);  // Ctrl + middle drag zooms (Blender)
    else
      orbit(in.delta_px);
  }
  if (in.wheel != 0) zoom(in.wheel, in.mouse_px, viewport);
  return alt_drag_;
}

}  // namespace trispline::editor
