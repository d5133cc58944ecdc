// trispline::editor::Navigator — Blender-like viewport navigation: an orbit camera around a pivot.
//
//   middle drag            orbit (turntable: yaw about world Y, pitch about the view's right axis)
//   Shift + middle drag    pan (the point under the cursor follows it at the pivot's depth)
//   wheel                  zoom toward the cursor (dolly; the pivot moves toward the point under the cursor)
//   Alt + left drag        orbit, Alt + Shift + left drag pan (trackpads)
//   F / Numpad .           frame the selected object's bounds; Home frames everything
//
// The app feeds it a NavInput built from ImGui's IO only when ImGui does not want the mouse/keyboard.
#pragma once

#include <glm/glm.hpp>

#include "core/mesh/tri_mesh.h"
#include "core/scene/camera.h"

namespace trispline::editor {

struct NavInput {
  glm::dvec2 mouse_px{0};  // cursor, viewport pixels (top-left origin)
  glm::dvec2 delta_px{0};  // cursor motion since the last frame, pixels
  double wheel = 0;        // wheel steps this frame (+ = away from the user = zoom in)
  bool middle_down = false, left_down = false;
  bool left_pressed = false;  // left button went down this frame (over the viewport)
  bool middle_pressed = false;
  bool shift = false, alt = false, ctrl = false;
};

// The navigation input of this frame from Dear ImGui's IO (GLFW backend), in framebuffer pixels.
NavInput nav_input_from_imgui();

class Navigator {
 public:
  // Takes pivot = camera.target, distance/yaw/pitch from camera.eye, fov and viewport from the camera.
  void set_from_camera(const core::Camera& camera);
  // Adopts `scene_camera` when it differs from the one seen last time (a camera.set command ran, an Open), backing
  // off if needed so that what it framed fits in the visible part of `viewport` (see set_visible_rect).
  void follow(const core::Camera& scene_camera, bool camera_set, glm::ivec2 viewport);
  // Adopts `scene_camera` now (after an Open, even if it equals the one seen last). Exactly as saved when its
  // viewport is `viewport` (the log was saved from a window of this size); else backed off as in follow().
  void adopt(const core::Camera& scene_camera, glm::ivec2 viewport);
  // The current view as a core::Camera with the given viewport size (pixels).
  core::Camera camera(glm::ivec2 viewport) const;

  // Applies mouse input. Returns true while the navigator owns the left button (Alt + left drag), so tools
  // must ignore it.
  bool update(const NavInput& in, glm::ivec2 viewport);

  void orbit(glm::dvec2 delta_px);                                     // 0.4 degrees per pixel
  void pan(glm::dvec2 delta_px, glm::ivec2 viewport);                  // pixels
  void zoom(double steps, glm::dvec2 cursor_px, glm::ivec2 viewport);  // 1 step = 15 % closer
  // Centres `box` in the visible part of the viewport (set_visible_rect: what the panels leave uncovered) and backs
  // off so it fits there (keeps yaw/pitch). Invalid boxes are ignored.
  void frame(const core::Aabb& box, glm::ivec2 viewport);
  // The part of the viewport not covered by panels, pixels [lo, hi) (top-left origin). Default: all of it.
  void set_visible_rect(glm::dvec2 lo_px, glm::dvec2 hi_px) {
    visible_lo_ = lo_px;
    visible_hi_ = hi_px;
  }

  glm::dvec3 pivot() const { return pivot_; }
  double distance() const { return distance_; }

 private:
  glm::dvec3 eye() const;
  glm::dvec2 visible_fraction(glm::ivec2 viewport) const;  // visible half extents / full half extents (x, y)
  glm::dvec3 pivot_{0.0, 0.5, 0.0};                        // world units
  double distance_ = 4.0;                                  // eye–pivot distance, world units
  double yaw_deg_ = 45.0;                                  // about +Y; 0 = looking along -Z
  double pitch_deg_ = 25.0;                                // above the horizon, clamped to (-89.5, 89.5)
  double fov_deg_ = 45.0;
  bool alt_drag_ = false;                         // an Alt + left drag is in progress
  glm::dvec2 visible_lo_{0.0}, visible_hi_{1e9};  // see set_visible_rect()
  core::Camera followed_;                         // scene camera adopted last (see follow())
  bool followed_set_ = false;
};

}  // namespace trispline::editor
