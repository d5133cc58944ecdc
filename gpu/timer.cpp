#include "gpu/timer.h"

#include "gpu/gl_context.h"

namespace trispline::gpu {

GpuTimer::GpuTimer(bool force_wall_clock)
    : mode_(force_wall_clock || is_software_renderer() ? Mode::wall_clock_finish : Mode::timer_query) {
  if (mode_ == Mode::timer_query)
    for (Query& q : queries_) q = Query::create();
}

const char* GpuTimer::mode_description() const {
  return mode_ == Mode::timer_query ? "GL_TIME_ELAPSED query" : "glFinish + wall clock (software renderer)";
}

void GpuTimer::poll() {
  // Oldest first, so last_ms_ ends up holding the newest available result.
  for (int k = 1; k <= 2; ++k) {
    const int i = (current_ + k) % 2;
    if (!pending_[i]) continue;
    GLint available = 0;
    glGetQueryObjectiv(queries_[i].id(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) continue;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &ns);
    last_ms_ = double(ns) * 1e-6;
    pending_[i] = false;
  }
}

void GpuTimer::begin() {
  if (mode_ == Mode::wall_clock_finish) {
    glFinish();
    start_ = std::chrono::steady_clock::now();
    return;
  }
  poll();
  // If both queries are still in flight (GPU two frames behind), reuse the older one: its result is dropped
  // rather than waited for.
  current_ = (current_ + 1) % 2;
  glBeginQuery(GL_TIME_ELAPSED, queries_[current_].id());
}

void GpuTimer::end() {
  if (mode_ == Mode::wall_clock_finish) {
    glFinish();
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    return;
  }
  glEndQuery(GL_TIME_ELAPSED);
  pending_[current_] = true;
  poll();
}

}  // namespace trispline::gpu
