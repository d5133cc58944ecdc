// trispline::editor::BackgroundCommand — a long command (ddm.fill, ddm.bake: Command::preparable) built on a worker
// thread while the editor keeps drawing and navigating, behind a progress bar with Cancel:
//   start      parses the line, copies the scene (objects share their meshes: a few pointers each) and runs
//              Command::prepare over the copy on a std::async thread, with a core::ProgressSink whose atomic cancel
//              flag the Cancel button sets; the session is busy (EditorSession::set_busy) meanwhile, so no other
//              command, undo, Open or New changes the document under it (they are refused with a Log warning, not
//              queued)
//   finish     UI thread, once per frame: when the worker is done, History runs the prepared command — redo only
//              swaps the built object in, so the session log gets the one line and the scene the bits a synchronous
//              execute gives. A cancel (even one that arrives after the build finished) or a failure changes nothing:
//              no history entry, no log line, the Log says "<verb> cancelled" or the error
//   progress   a small window at the bottom of the viewport (not modal: the view keeps orbiting): what, a bar, Cancel
// A line whose command is not preparable runs at once, as EditorSession::execute.
// Undo, redo and History jumps go the same way (start_history): the steps run over a copy of the scene on the worker
// (History::walk: a redo of a heavy command — a volume load, a fill — takes its time there), and finish() makes the
// walked copy the document in one go (EditorSession::settle_history). A cancel or a failing step changes nothing.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/commands/command.h"
#include "core/scene/scene.h"
#include "editor/session/session.h"
#include "ui/layout.h"

namespace trispline::editor {

class BackgroundCommand {
 public:
  explicit BackgroundCommand(EditorSession& session);
  ~BackgroundCommand();  // cancels the build under way and waits for its thread
  BackgroundCommand(const BackgroundCommand&) = delete;
  BackgroundCommand& operator=(const BackgroundCommand&) = delete;

  // Starts `line` (a command's JSON line; relative paths against the current folder, as EditorSession::execute).
  // `what`: the progress window's text ("Filling teapot with thorn"); `verb`: the Log's "<verb> cancelled" ("Fill").
  // A parse error goes to the Log (false); a command that is not preparable runs at once (its success). False with a
  // Log warning while another build runs or the session is busy.
  bool start(const nlohmann::json& line, std::string what, std::string verb);
  // Moves the session's history to position `target` (clamped to its size; EditorSession::jump_to's meaning): undo
  // is target = applied − 1, redo applied + 1. False when there is nothing to move, or with a Log warning while
  // another job runs or the session is busy.
  bool start_history(std::size_t target);
  // Opens `log` (EditorSession::open) with its replay on the worker: progress by log line, Cancel between lines;
  // `opened` runs on the UI thread after the document became the opened log. False with a Log warning while another
  // job runs or the session is busy.
  bool start_open(const std::filesystem::path& log, std::function<void()> opened);
  bool running() const { return job_ != nullptr; }
  double progress() const;          // [0, 1] of the build under way (0 when none)
  const std::string& what() const;  // the build under way's text ("" when none)
  // Asks the build to stop: its worker throws core::OperationCancelled at its next progress check, and finish()
  // discards whatever it made.
  void cancel();
  bool cancelling() const { return job_ && job_->cancel.load(); }
  // Blocks until the worker is done (tests; finish() still has to run).
  void wait() const;
  // UI thread, once per frame: when the worker is done, executes the prepared command through the session (one
  // history entry, one log line) or reports the cancel / failure in the Log. True when a command was executed.
  bool finish();
  // The progress window over `viewport` (ImGui screen pixels); between NewFrame and Render. Probe items
  // "command.progress" (its value: the percentage, "45 %") and "command.cancel".
  void draw_progress(const ui::Rect& viewport);

 private:
  struct Job {
    core::CommandPtr command;
    std::string what, verb;
    std::uint64_t changes = 0;  // EditorSession::change_count() at start
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    std::chrono::steady_clock::time_point started;
    std::future<void> future;
    std::optional<std::size_t> target;                 // a history move (start_history) rather than a command
    std::optional<core::Scene> walked;                 // its scene, set by the worker
    std::unique_ptr<EditorSession::OpenedLog> opened;  // an Open (start_open), set by the worker
    std::function<void()> after_open;
  };
  // True, with a Log warning naming what `what` waits for, while a job runs or the session is busy.
  bool refused(const std::string& what) const;
  EditorSession& session_;
  std::unique_ptr<Job> job_;
};

}  // namespace trispline::editor
