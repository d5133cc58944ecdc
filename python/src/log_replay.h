// trispline::python log replay without a GPU: Scene.open (re-create a scene from a log, writing no files, as the
// editor's Open) and trispline.replay (a headless replay writing report.json and scene.glb, as `trispline replay`).
// Lines are read by the command layer's reader (editor/commands/command_log.h: limits, UTF-8, nesting) and run
// through PyScene::run, so a log line, Scene.run and `trispline replay` validate and execute a command alike.
// What `trispline replay` adds and this module cannot (it has no gpu layer): final.png, the GPU FFD backends,
// recordings of anim.record lines (report "record_error").
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "python/src/py_scene.h"

namespace trispline::python {

struct LogRun {
  bool ok = true;
  std::string error;  // "LOG:LINE: field 'x': message" when !ok
  std::string field;  // the failing field, "" when none
  int failed_line = 0;
  double ms = 0;                                      // wall time of the whole replay
  nlohmann::json commands = nlohmann::json::array();  // report.json's entries {line, cmd, ok, ms, [error], [stats]}
  bool records = false;                               // the log holds anim.record lines
};

// Runs every line of `log` into `scene` (relative input paths against the log's folder), stopping at the first
// failing line. write_files: whether commands that write files (volume.export) write them, under `output_dir`.
LogRun run_log(PyScene& scene, const std::filesystem::path& log, const std::filesystem::path& output_dir,
               bool write_files);

// `trispline replay LOG --out DIR` without the GPU: replays `log` into a new scene, writes DIR/scene.glb (the CPU
// reference geometry) and DIR/report.json, and returns the report (report.json's schema, editor/replay/replay.h,
// with "final_png_error" saying why there is no image). Throws std::runtime_error when DIR cannot be created.
nlohmann::json replay_log(const std::filesystem::path& log, const std::filesystem::path& out_dir);

}  // namespace trispline::python
