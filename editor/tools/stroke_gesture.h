// trispline::editor::StrokeGesture — the press / drag / release of a stroke drawn in the viewport, shared by the
// tools that draw strokes (Sketch placement, Incision, Tile paint). It collects viewport pixels (top-left origin)
// while the left button is down, dropping points closer than kMinSpacingPx to the previous one, and keeps the view
// at mouse-down: the stroke's pixels belong to it whatever the camera does until mouse-up.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/scene/camera.h"
#include "editor/tools/tool.h"

namespace trispline::editor {

class StrokeGesture {
 public:
  static constexpr double kMinSpacingPx = 2.0;  // pixels

  enum class Event { None, Began, Moved, Ended };

  // Feeds one frame's input. Began: the button went down (points() holds the first point, view() the view);
  // Moved: a point was added while drawing; Ended: the button came up (take() the stroke) — also in the frame it
  // went down, for a click that lasted less than a frame.
  Event update(const ToolInput& in, const core::Camera& view) {
    const bool up = in.left_released || !in.left_down;
    if (in.left_pressed) {
      points_ = {in.mouse_px};
      view_ = view;
      drawing_ = !up;
      return up ? Event::Ended : Event::Began;
    }
    if (!drawing_) return Event::None;
    bool moved = false;
    if (in.left_down && glm::length(in.mouse_px - points_.back()) >= kMinSpacingPx) {
      points_.push_back(in.mouse_px);
      moved = true;
    }
    if (up) {
      drawing_ = false;
      return Event::Ended;
    }
    return moved ? Event::Moved : Event::None;
  }

  bool drawing() const { return drawing_; }
  const std::vector<glm::dvec2>& points() const { return points_; }  // #S × 2 viewport pixels
  const core::Camera& view() const { return view_; }                 // the view at mouse-down
  // The stroke, leaving the gesture empty.
  std::vector<glm::dvec2> take() {
    std::vector<glm::dvec2> out = std::move(points_);
    points_.clear();
    return out;
  }
  void cancel() {
    drawing_ = false;
    points_.clear();
  }

 private:
  std::vector<glm::dvec2> points_;
  core::Camera view_;
  bool drawing_ = false;
};

}  // namespace trispline::editor
