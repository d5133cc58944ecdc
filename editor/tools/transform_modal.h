// trispline::editor::TransformModal — Blender's modal G / R / S on the selected object.
//
//   G grab (move in the view plane), R rotate (about the view axis), S scale (by the cursor's distance to the pivot)
//   X / Y / Z        constrain to that world axis (the same key again clears it); for S, the object's own axis
//   0-9 . - ⌫        type the value exactly (a move along the axis, X without one; degrees; a factor); - negates
//   G / R / S        switch mode (starts again from the original transform)
//   Enter, left click      confirm: one object.transform line with the absolute result
//   Esc, right click       cancel: nothing is executed, the object was never changed
//
// The modal never touches the document while it runs: the app draws preview_object() in place of the object (its
// lattice moved with it, its evaluation mapped affinely, core::object_with_transform(…, false)). Input comes as
// GLFW key presses in order (ui::ImGuiHost::key_presses), so keys typed faster than the frame rate all count; nothing
// depends on frame timing. The pivot is the object's origin (its location, as in Blender), or the centre of its
// evaluated bounds when a lattice has moved the shape away from it (placed, ring, DFFD objects).
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "ui/imgui_host.h"

namespace trispline::editor {

enum class TransformMode { grab, rotate, scale };

// One frame of input for the modal: key presses in order, the cursor (viewport pixels, top-left origin) and clicks.
struct TransformModalInput {
  std::vector<ui::KeyPress> keys;
  glm::dvec2 mouse_px{0.0};
  bool left_clicked = false;
  bool right_clicked = false;
};

class TransformModal {
 public:
  enum class Outcome { running, confirmed, cancelled };

  // The G / R / S key that starts a modal (GLFW key code, no modifiers); nullopt for any other key.
  static std::optional<TransformMode> start_key(const ui::KeyPress& k);

  // Starts on `object` seen through `view`, the cursor at `mouse_px`.
  void begin(TransformMode mode, const core::SceneObject& object, const core::Camera& view, glm::dvec2 mouse_px);
  bool active() const { return active_; }
  // Feeds keys from `first` on (earlier ones were not the modal's) and the cursor. Returns confirmed / cancelled
  // once (the modal is then inactive) with the line to execute in confirmed_line().
  Outcome update(const TransformModalInput& in, std::size_t first = 0);

  const std::string& object() const { return object_; }
  TransformMode mode() const { return mode_; }
  int axis() const { return axis_; }  // -1 = none, 0/1/2 = x/y/z
  const core::Transform& start_transform() const { return start_; }
  core::Transform current() const;  // what the object would get now
  // The object as previewed now (shared meshes when nothing moved yet). Cached per transform.
  const core::SceneObject& preview_object();
  // The object.transform line of the last confirm.
  const nlohmann::json& confirmed_line() const { return confirmed_; }
  // "Grab  X: 1.500  (Esc cancel, Enter confirm)", "Rotate  [90|]  Z: 90.00 deg  (…)", "Scale  2.000  (…)": what is
  // happening, for a line at the bottom of the viewport and the status bar.
  std::string header() const;

 private:
  bool key(const ui::KeyPress& k);  // false when the key ends the modal (outcome_ set)
  bool typing() const { return !text_.empty() || negative_; }
  double typed_value() const;
  double angle_deg() const;  // R: the turn, degrees (typed, or swept by the cursor around the pivot)
  double factor() const;     // S: the scale factor (typed, or the cursor's distance ratio)
  void restart(TransformMode mode);

  bool active_ = false;
  Outcome outcome_ = Outcome::running;
  TransformMode mode_ = TransformMode::grab;
  int axis_ = -1;
  std::string text_;  // typed digits and '.'
  bool negative_ = false;
  std::string object_;
  core::SceneObject original_;
  core::Transform start_;
  core::Camera view_;
  glm::dvec3 pivot_{0.0};       // world units
  glm::dvec2 pivot_px_{0.0};    // its viewport pixel
  double units_per_px_ = 0.01;  // world units per pixel at the pivot's depth
  glm::dvec2 mouse0_{0.0}, mouse_{0.0};
  nlohmann::json confirmed_;
  std::optional<core::SceneObject> preview_;
  core::Transform preview_for_;
};

// Rotation R (a pure rotation matrix) as rotate_deg of core::Transform (R = Rz·Ry·Rx), degrees, each in (−180, 180].
glm::dvec3 euler_xyz_deg(const glm::dmat3& r);

}  // namespace trispline::editor
