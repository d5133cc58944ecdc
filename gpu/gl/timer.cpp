#include "gpu/gl/timer.h"

#include "gpu/gl/gl_context.h"

namespace trispline::gpu {

GpuTimer::GpuTimer(bool force_wall_clock)
    : GpuTimer(force_wall_clock || is_software_renderer() ? Mode::wall_clock_finish : Mode::timer_query) {}

GpuTimer::GpuTimer(Mode mode) : mode_(mode) {
  if (mode_ == Mode::timer_query)
    for (Query& q : queries_) q = Query::create();
}

const char* GpuTimer::describe(Mode mode) {
  return mode == Mode::timer_query
             ? "GPU: GL_TIME_ELAPSED queries"
             : "GPU: glFinish + wall clock (software renderer: llvmpipe timer queries are unreliable)";
}

int GpuTimer::in_flight() const {
  int n = 0;
  for (long s : issued_) n += s != 0;
  return n;
}

void GpuTimer::collect() {
  if (mode_ != Mode::timer_query) return;
  for (int i = 0; i < kQueriesInFlight; ++i) {
    if (issued_[i] == 0 || i == active_) continue;
    GLint available = 0;
    glGetQueryObjectiv(queries_[i].id(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) continue;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &ns);  // available: does not wait
    if (issued_[i] > newest_read_) {  // results may become available out of order: keep the newest
      newest_read_ = issued_[i];
      last_ms_ = double(ns) * 1e-6;
    }
    issued_[i] = 0;
  }
}

void GpuTimer::begin() {
  if (mode_ == Mode::wall_clock_finish) {
    glFinish();
    start_ = std::chrono::steady_clock::now();
    return;
  }
  collect();
  active_ = -1;
  for (int i = 0; i < kQueriesInFlight; ++i)
    if (issued_[i] == 0) {
      active_ = i;
      break;
    }
  if (active_ < 0) {  // the GPU is kQueriesInFlight frames behind: skip rather than wait
    ++skipped_;
    return;
  }
  issued_[active_] = ++sequence_;
  glBeginQuery(GL_TIME_ELAPSED, queries_[active_].id());
}

void GpuTimer::end() {
  if (mode_ == Mode::wall_clock_finish) {
    glFinish();
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return;
  }
  if (active_ < 0) return;  // skipped
  glEndQuery(GL_TIME_ELAPSED);
  active_ = -1;
  collect();
}

}  // namespace trispline::gpu
