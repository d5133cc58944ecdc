// trispline::editor replay — runs a command log headlessly: `trispline replay LOG --out DIR`.
//
// report.json: {"log", "ok", "replay_ms", ["error", "failed_line"], "commands": [{"line","cmd","ok","ms","stats"}],
//   "objects": [{"name","vertices","triangles","deformed"}], "ffd_backend", "time_s", "scene_glb" | "scene_glb_error",
//   "final_png" | "final_png_error", "renderer", "render_ms",
//   "timings": the live timing overlay's numbers (ui/overlays.h) —
//     "commands": [{"line","cmd","total_ms","stages_ms":{"fit":..,"rays":..}}]   CPU ms per command and stage
//     "geometry": {"source"[,"objects","vertices","ms","renderer"]}  which backend evaluated scene.glb (ms: wall time
//                 incl. shader builds and read-back)
//     "render": {"ffd_backend","ffd_backend_label","renderer","timer_mode","time_s","ffd_objects","ffd_vertices",
//                "ffd_ms","draw_ms","vertices_per_second"}   the final.png frame's GPU passes (null = not measured),
//   "record": RecordResult::to_json() of the recording (--frames, or the log's last anim.record line),
//   "records": [...] every recording when the log holds more than one anim.record line, "record_error"}
//
// Recordings (editor/replay/record.h): with --frames A-B the final scene's frames A..B are written into DIR
// (frame_NNNN.png|exr and animation.glb of that range; no MP4: a slice of a render farm), after checking the range
// against the timeline — a range outside it exits 2 before anything is written. Without --frames, every anim.record
// line of the log is recorded as the editor did when it ran, from the scene at that line, into DIR itself (the
// line's "out" is the editor's folder; a later recording overwrites files of the same name). With --piece-base F
// the chunk writes animation.piece (morph targets relative to frame F) instead, for `trispline farm assemble`.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"
#include "editor/commands/history.h"
#include "editor/replay/record.h"

namespace trispline::editor {

struct ReplayOptions {
  std::filesystem::path log;
  std::filesystem::path out_dir;  // empty: no outputs written
  int width = 0, height = 0;      // final.png size; 0 = the last camera.set viewport (default 1280×720)
  bool render = true;             // write final.png (needs an EGL context)
  // Backend that evaluates the deformed objects for final.png and, unless cpu_ref, for scene.glb (read back from the
  // GPU for GLSL backends, so the GPU path is tested end to end). cpu_ref: the authoritative CPU geometry.
  core::FfdBackend ffd_backend = core::FfdBackend::cpu_ref;
  double time_s = 0;  // scene time, seconds: animated objects (lattice.animate_offset) are shown and exported at it
  // --frames A-B: record timeline frames [frames.frame_first, frames.frame_last] into out_dir at width × height
  // (see above); --format png|exr (frames.format); --piece-base F (frames.piece_base): animation.piece relative to
  // frame F instead of animation.glb (a farm chunk). out_dir, width and height come from the fields above; no MP4.
  bool frames_given = false;
  RecordOptions frames;
};

struct ReplayResult {
  bool ok = true;
  std::string error;  // "LOG:LINE: field 'x': message" when !ok
  int failed_line = 0;
  std::vector<ExecutionRecord> records;
};

// Called after a log line's command executed successfully (not for edit.undo / edit.redo), with the command (as
// held by the history) and its 1-based log line; the history's scene is in the state right after it.
using ReplayHook = std::function<void(const core::Command& command, int log_line)>;

// Whether a replay writes the files of the commands that write files (core::FileOutput: volume.export, anim.record).
enum class FileWrites {
  write,  // headless replay: under its --out folder
  skip,   // the editor's Open and crash recovery: the scene is re-created, no file is written (History: Run again)
};

// Replays `lines` of a log into `history` (and its scene). Stops at the first failing line. Relative paths of files
// the log's commands write (volume.export) go under `output_dir` (empty: the log's folder); with FileWrites::skip
// none is written.
ReplayResult replay_lines(History& history, const std::filesystem::path& log_path, const ReplayHook& on_executed = {},
                          const std::filesystem::path& output_dir = {}, FileWrites writes = FileWrites::write);
// "A-B" (or "A" for one frame): non-negative frame numbers, A ≤ B; nullopt for anything else.
std::optional<std::pair<int, int>> parse_frame_range(const std::string& text);

// Full CLI behaviour: replay, then write DIR/final.png, DIR/scene.glb, the recordings, DIR/report.json. Returns the
// exit code: 0, 2 when the log fails or --frames lies outside the timeline, 3 when an output cannot be written (or
// the chosen backend fails).
int run_replay(const ReplayOptions& options);

}  // namespace trispline::editor
