// Internal to editor/: wall-clock milliseconds since a steady_clock time point (the reports' and overlays' "ms").
#pragma once

#include <chrono>

namespace trispline::editor {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace trispline::editor
