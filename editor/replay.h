// trispline::editor replay — runs a command log headlessly: `trispline replay LOG --out DIR`.
#pragma once

#include "core/scene/scene.h"
#include "editor/history.h"

#include <filesystem>
#include <string>
#include <vector>

namespace trispline::editor {

struct ReplayOptions {
  std::filesystem::path log;
  std::filesystem::path out_dir;  // empty: no outputs written
  int width = 0, height = 0;      // final.png size; 0 = the last camera.set viewport (default 1280×720)
  bool render = true;             // write final.png (needs an EGL context)
};

struct ReplayResult {
  bool ok = true;
  std::string error;   // "LOG:LINE: field 'x': message" when !ok
  int failed_line = 0;
  std::vector<ExecutionRecord> records;
};

// Replays `lines` of a log into `history` (and its scene). Stops at the first failing line.
ReplayResult replay_lines(History& history, const std::filesystem::path& log_path);
// Full CLI behaviour: replay, then write DIR/final.png, DIR/scene.glb, DIR/report.json. Returns exit code.
int run_replay(const ReplayOptions& options);

}  // namespace trispline::editor
