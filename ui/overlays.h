// trispline::ui viewport overlays, drawn over the 3-D view:
//  * TimingOverlay: the live timing overlay (View > Timing overlay, F7) in the viewport's top-left corner:
//    FPS and frame time; per pass FFD evaluation, rendering, volume ray casting (with volumes) and UI (ms); FFD
//    vertices per second; the live silhouettes' extraction time; a graph of the last 5 seconds, one line per pass;
//    the GPU timing method; the FFD evaluator in use; the last command's CPU time per stage. Every number explains
//    itself in a tooltip. A small ImGui window with an opaque-ish background, so it reads over light and dark scenes.
//  * draw_working_overlay(): the "Working..." box shown for one frame before a long synchronous command runs.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "ui/frame_timings.h"
#include "ui/layout.h"

namespace trispline::ui {

// One frame's figures, as the editor measured them.
struct FrameSample {
  double time_s = 0;       // when the frame ended, seconds on any monotonic clock
  double work_ms = 0;      // CPU wall time spent on the frame (events to swap)
  double interval_ms = 0;  // time since the previous frame (includes idle waiting; gives the FPS)
  PassTimings passes;      // GPU passes (negative = not measured)
};

// What the overlay names besides the per-frame numbers (set whenever it changes).
struct TimingContext {
  std::string timer_mode;    // GpuTimer::describe(): "GPU: GL_TIME_ELAPSED queries" / "GPU: glFinish + wall clock ..."
  std::string ffd_backend;   // ffd_backend_label() of the evaluator in use
  double scene_time_s = -1;  // playback time of animated objects, seconds (negative: no animated object)
  bool playing = false;      // the playback clock runs
  std::string last_command;  // id of the command on top of the undo stack ("" = none)
  double last_command_ms = -1;           // its wall time when executed (negative = unknown)
  std::vector<StageTiming> last_stages;  // its CPU time per stage, stage_timings(stats())
  // Live silhouettes of volumes (extracted on a worker thread for the current view): the last extraction's wall time
  // (negative: none) and points, and whether one is running now.
  double silhouette_ms = -1;
  std::size_t silhouette_points = 0;
  bool silhouette_running = false;
  // Guarantees (View > Error bounds / Fold certificate) of the object shown: the last computation's cost in ms
  // (negative: not shown) and its summary.
  double bounds_ms = -1;
  double certificate_ms = -1;
  std::string guarantees;
  // Live tile layers (gpu::RenderStats): instances of the drawn layers, those drawn, those culled, and the motion
  // LOD's share of the rest (1 = full detail).
  std::size_t ddm_instances = 0, ddm_drawn = 0, ddm_culled = 0;
  double ddm_keep = 1.0;
};

// The overlay's tile line: "tiles 5,120 of 20,480 drawn (moving: 1/4, culled 9,800)"; the parts in brackets only
// when they apply; "" without tile instances.
std::string ddm_tiles_text(const TimingContext& context);

class TimingOverlay {
 public:
  static constexpr double kGraphSeconds = 5.0;    // the graph's time span
  static constexpr double kAverageSeconds = 1.0;  // the numbers are means over this much of the newest frames

  void add_frame(const FrameSample& sample);  // keeps the last kGraphSeconds (and at most 2000 frames)
  void set_context(TimingContext context) { context_ = std::move(context); }
  const TimingContext& context() const { return context_; }

  // The numbers the overlay shows (negative = unknown). Frame, render and UI: means over the last kAverageSeconds.
  // FFD: GLSL compute and the CPU paths evaluate only when a deformation changes, so the FFD figures are means over
  // the frames that evaluated (ffd_vertices > 0) in the last second, else those of the last frame that did
  // (ffd_recent false) — an evaluation stays readable after the frame that made it.
  struct Summary {
    std::size_t frames = 0;  // frames averaged
    bool idle = false;       // the editor was waiting for input: fps is meaningless then
    double fps = -1, frame_ms = -1, draw_ms = -1, ui_ms = -1;
    double volume_ms = -1;            // iso-surface pass (ray casting when the view or a level changed), mean
    double ffd_ms = -1;               // FFD pass of the evaluating frames
    double ffd_vertices = 0;          // vertices per evaluating frame
    double vertices_per_second = -1;  // ffd_vertices / ffd_time_ms() (render time for the vertex-shader path)
    bool ffd_recent = false;          // the FFD figures come from the last second
    bool ffd_in_draw = false;         // the evaluation ran in the render pass (vertex-shader path)
  };
  Summary summary() const;
  std::size_t sample_count() const { return samples_.size(); }

  // Draws the overlay as a small window at the viewport's top-left corner. Call between NewFrame and Render.
  void draw(const Rect& viewport) const;

 private:
  void draw_graph(float width, float height) const;
  std::deque<FrameSample> samples_;  // oldest first
  FrameSample last_eval_;            // newest sample with ffd_vertices > 0, if has_eval_
  bool has_eval_ = false;
  TimingContext context_;
};

// Begins a borderless, auto-sized overlay window `id` ("##timing_overlay") over the viewport, dark with light text so
// that it reads over any object: its corner (`pivot_x`, `pivot_y`) — (0,0) top-left … (1,1) bottom-right — at
// (`corner_x`, `corner_y`) in window pixels, `alpha` its background's opacity. False when there is nothing to draw (the
// window is already ended); otherwise end it with ImGui::End().
bool begin_viewport_overlay(const char* id, float corner_x, float corner_y, float pivot_x, float pivot_y, float alpha);

// Dims the whole window and shows `text` ("Working...: placing bunny") in a centred box.
void draw_working_overlay(const std::string& text);

}  // namespace trispline::ui
