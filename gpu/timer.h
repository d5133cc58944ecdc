// trispline::gpu::GpuTimer — times a GPU pass for the live timing overlay (issue 3) without stalling.
//
// Query mode (real GPUs): GL_TIME_ELAPSED queries, double-buffered: begin()/end() of frame N records into one
// query, and last_ms() reports the newest *available* result (normally frame N-1's); results are only read when
// GL_QUERY_RESULT_AVAILABLE says so, so the CPU never waits on the GPU.
// Wall-clock mode (software renderers, see is_software_renderer(): llvmpipe's timer queries return nonsense):
// begin() and end() call glFinish() and measure steady_clock in between; last_ms() is this frame's result.
#pragma once

#include <array>
#include <chrono>

#include "gpu/gl_resource.h"

namespace trispline::gpu {

class GpuTimer {
 public:
  enum class Mode { timer_query, wall_clock_finish };
  // Picks the mode for the current context (needs one). `force_wall_clock` forces the glFinish mode.
  explicit GpuTimer(bool force_wall_clock = false);
  void begin();  // must not nest with another GL_TIME_ELAPSED query
  void end();
  // Milliseconds of the newest finished measurement; negative until one is available.
  double last_ms() const { return last_ms_; }
  Mode mode() const { return mode_; }
  // "GL_TIME_ELAPSED query" or "glFinish + wall clock (software renderer)", for the overlay's label.
  const char* mode_description() const;

  // RAII begin/end.
  class Scope {
   public:
    explicit Scope(GpuTimer& t) : t_(t) { t_.begin(); }
    ~Scope() { t_.end(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GpuTimer& t_;
  };

 private:
  void poll();  // collects finished query results without waiting
  Mode mode_;
  std::array<Query, 2> queries_;
  std::array<bool, 2> pending_{false, false};
  int current_ = 0;
  double last_ms_ = -1.0;
  std::chrono::steady_clock::time_point start_{};
};

}  // namespace trispline::gpu
