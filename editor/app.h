// trispline::editor interactive editor — run_editor() opens the GLFW window with the Dear ImGui panels around the
// 3-D viewport and runs until the user quits (`trispline`, `trispline edit [LOG]`).
//
// Panels: Scene (top right), History (bottom right), Tool (left), Log (bottom), main menu, status bar.
// Every change goes through a command (History + session log, see editor/session/session.h); errors go to the Log
// panel.
#pragma once

#include <filesystem>

namespace trispline::editor {

struct AppOptions {
  std::filesystem::path open_log;  // replayed at start into the history (each line one undoable step)
  bool recover_prompt = true;      // offer to recover an unfinished previous session
  int width = 1600, height = 900;  // window size, screen coordinates
  // If set: run the start-up work, render a few frames with every panel open, write a PNG of the whole window
  // (UI included) to this path and exit (README screenshots under xvfb). No session log is written then.
  std::filesystem::path screenshot;
  // GUI tests (tests/gui): write the probe JSON (editor/gui_probe.h) to this path after every frame.
  std::filesystem::path gui_probe;
  // > 0: at most this many frames per second (GUI tests reproduce software-GL frame rates, e.g. 3).
  double max_fps = 0.0;
  // Frames a second while nothing changes (0: an idle editor draws nothing until an event, a background result or
  // playback wakes it). GUI tests pass their frame rate: their waits count frames.
  double idle_fps = 0.0;
  // `trispline bench editor`: if set, open_log is replayed and, once it is loaded and the view has settled, the
  // editor draws `bench_frames` frames with nothing changed (idle: what a redraw costs) and as many orbiting the view
  // 3° a frame about its pivot, writes the frame times to this path as JSON and exits (no session log is written):
  //   {"idle_ms":[…], "orbit_ms":[…], "viewport":[w, h] (pixels), "gl_renderer":"…",
  //    "silhouette_ms":[…] (the extractions that finished while orbiting, each its own duration)}
  // A frame is timed from its start to the end of glFinish after the swap, milliseconds.
  std::filesystem::path bench_out;
  int bench_frames = 30;
};

// Runs the editor. Returns the exit code: 0 on a normal quit (or a written screenshot), 1 if the screenshot
// could not be written, 2 if no window could be created (the reason is printed on stderr). Never throws.
int run_editor(const AppOptions& options);

}  // namespace trispline::editor
