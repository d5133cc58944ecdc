// trispline::ui viewport overlays, drawn on ImGui's foreground/background draw lists over the 3-D view:
//  * TimingOverlay: FPS and frame milliseconds (medians of the last 120 frames) in the viewport's top-left corner, with
//  a small frame-time graph
//    (issue 3 extends it with GPU/CPU stage timings).
//  * draw_working_overlay(): the "Working…" box shown for one frame before a long synchronous command runs.
#pragma once

#include "ui/layout.h"

#include <array>
#include <string>

namespace trispline::ui {

class TimingOverlay {
 public:
  // Once per frame: work_ms = CPU+GPU time spent on the frame (events to swap), interval_ms = time since the
  // previous frame (includes idle waiting; gives the FPS).
  void add_frame(double work_ms, double interval_ms);
  void draw(const Rect& viewport) const;

 private:
  static float median(const std::array<float, 120>& ring, std::size_t count);
  std::array<float, 120> history_{}, intervals_{};  // frame work / interval ms, ring buffers
  std::size_t next_ = 0, count_ = 0;
};

// Dims the whole window and shows `text` ("Working…: placing bunny") in a centred box.
void draw_working_overlay(const std::string& text);

}  // namespace trispline::ui
