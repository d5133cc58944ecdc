// trispline::editor interactive editor — run_editor() opens the GLFW window with the Dear ImGui panels around the
// 3-D viewport and runs until the user quits (`trispline`, `trispline edit [LOG]`).
//
// Panels: Scene (top right), History (bottom right), Tool (left), Log (bottom), main menu, status bar.
// Every change goes through a command (History + session log, see editor/session.h); errors go to the Log panel.
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
};

// Runs the editor. Returns the exit code: 0 on a normal quit (or a written screenshot), 1 if the screenshot
// could not be written, 2 if no window could be created (the reason is printed on stderr). Never throws.
int run_editor(const AppOptions& options);

}  // namespace trispline::editor
