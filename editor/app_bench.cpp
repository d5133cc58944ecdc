// Bench mode of the editor (AppOptions::bench_out, `trispline bench editor`): the real frame loop, timed. The log
// opens on its worker as in normal use; once nothing is pending for kSettleFrames frames in a row the editor draws
// AppOptions::bench_frames frames with nothing changed, then as many orbiting the view 3° a frame (7.5 pixels of a
// left-button orbit drag, 0.4° a pixel), and writes the frame times.
#include <fstream>
#include <nlohmann/json.hpp>

#include "editor/app_state.h"

namespace trispline::editor {
namespace {

constexpr int kSettleFrames = 5;
constexpr double kOrbitPixelsPerFrame = 7.5;  // 3° (Navigator::orbit: 0.4° a pixel)

}  // namespace

void App::bench_before_frame() {
  const int n = options_.bench_frames;
  if (bench_->settled >= kSettleFrames && static_cast<int>(bench_->idle_ms.size()) >= n)
    nav_.orbit({kOrbitPixelsPerFrame, 0.0});
}

int App::bench_after_frame(Clock::time_point start) {
  glFinish();  // the frame's GL work is done (llvmpipe draws when the swap or a finish asks for it)
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  Bench& b = *bench_;
  const int n = options_.bench_frames;
  if (b.settled < kSettleFrames) {
    const bool quiet =
        work_.empty() && !background_.running() && !volumes_.busy() && !guarantees_.busy() &&
        !(renderer_ && (renderer_->last_stats().volume_refining || renderer_->last_stats().ddm_keep < 1.0));
    b.settled = quiet ? b.settled + 1 : 0;
    b.silhouettes_seen = volumes_.finished();
    return -1;
  }
  if (static_cast<int>(b.idle_ms.size()) < n) {
    b.idle_ms.push_back(ms);
    b.silhouettes_seen = volumes_.finished();
    return -1;
  }
  b.orbit_ms.push_back(ms);
  if (volumes_.finished() != b.silhouettes_seen) {
    b.silhouettes_seen = volumes_.finished();
    b.silhouette_ms.push_back(volumes_.last_extract_ms());
  }
  if (static_cast<int>(b.orbit_ms.size()) < n) return -1;
  const glm::ivec2 fb = window_->framebuffer_size();
  const nlohmann::json out = {{"idle_ms", b.idle_ms},
                              {"orbit_ms", b.orbit_ms},
                              {"viewport", {view_.viewport.x, view_.viewport.y}},
                              {"window", {fb.x, fb.y}},
                              {"gl_renderer", gl_renderer_},
                              {"silhouette_ms", b.silhouette_ms},
                              {"log_errors", messages_.error_count()}};
  std::ofstream file(options_.bench_out);
  file << out.dump(1) << '\n';
  if (!file) {
    std::cerr << "trispline: cannot write " << options_.bench_out << '\n';
    return 1;
  }
  return 0;
}

}  // namespace trispline::editor
