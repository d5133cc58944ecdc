// trispline::gpu::GpuTimer — times a GPU pass (FFD evaluation, scene draw, ImGui) for the live timing overlay and
// replay's report.json without ever making the CPU wait for the GPU.
//
// Query mode (real GPUs): a ring of kQueriesInFlight GL_TIME_ELAPSED queries. begin()/end() of frame N record into
// the next free query; last_ms() is the newest result GL_QUERY_RESULT_AVAILABLE reports finished (normally frame
// N-1 or N-2). Results are only read once available. When every query is still in flight (the GPU is
// kQueriesInFlight frames behind) that frame is not measured (skipped() counts it) rather than reusing a pending
// query, which some drivers implement by waiting.
// Wall-clock mode (software renderers, see is_software_renderer(): llvmpipe's timer queries return wrong values,
// ../shared/DEBIAN-NOTES.md): begin() and end() call glFinish() and measure steady_clock in between; last_ms() is this
// pass's result at once. This stalls by design: on a software renderer the "GPU" is the CPU anyway.
//
// One GL_TIME_ELAPSED query can be active at a time: timers must not nest (sequential passes are fine).
#pragma once

#include <array>
#include <chrono>

#include "gpu/gl/gl_resource.h"

namespace trispline::gpu {

class GpuTimer {
 public:
  enum class Mode { timer_query, wall_clock_finish };
  static constexpr int kQueriesInFlight = 3;

  // Picks the mode for the current context (needs one): wall clock on a software renderer, queries otherwise.
  // `force_wall_clock` forces the glFinish mode.
  explicit GpuTimer(bool force_wall_clock = false);
  // Forces a mode (tests exercise the query ring on llvmpipe, where its values are meaningless but the protocol runs).
  explicit GpuTimer(Mode mode);

  void begin();  // must not nest with another GL_TIME_ELAPSED query
  void end();
  // Reads finished query results without waiting (begin() and end() do it too). No-op in wall-clock mode.
  void collect();

  // Milliseconds of the newest finished measurement; negative until one is available.
  double last_ms() const { return last_ms_; }
  Mode mode() const { return mode_; }
  int in_flight() const;  // queries issued whose results have not been read yet (≤ kQueriesInFlight)
  long skipped() const { return skipped_; }  // frames not measured because every query was in flight
  // The overlay's "GPU: ..." line for this timer's mode, see describe().
  const char* mode_description() const { return describe(mode_); }
  // "GPU: GL_TIME_ELAPSED queries" or "GPU: glFinish + wall clock (software renderer: llvmpipe timer queries are
  // unreliable)".
  static const char* describe(Mode mode);

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
  Mode mode_;
  std::array<Query, kQueriesInFlight> queries_;
  std::array<long, kQueriesInFlight> issued_{};  // sequence number of the measurement held (0 = none pending)
  long sequence_ = 0;                            // measurements issued so far
  long newest_read_ = 0;                         // sequence number behind last_ms_
  int active_ = -1;                              // query between begin() and end(), -1 if none (or skipped)
  long skipped_ = 0;
  double last_ms_ = -1.0;
  std::chrono::steady_clock::time_point start_{};
};

}  // namespace trispline::gpu
