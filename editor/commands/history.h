// trispline::editor::History — the undo stack over a Scene, and the session's command log.
//
// execute(cmd): runs cmd->redo(scene); a result that is not finite or lies out of range (core::SceneGuard) is undone
// at once and reported as a CommandError; on success pushes it (dropping the redo tail) and appends its JSON line
// to the log (flushed at once); a command that is not undoable() (anim.record) is run and logged, never pushed. On
// failure the scene is unchanged, nothing is pushed, and the CommandError is rethrown for the caller to report.
// A non-undoable command is kept as an Output after the commands applied when it ran (the History panel shows it
// there), with a copy of the scene when its files were not written (core::FileOutput), so Run again can write them
// from the scene it saw; outputs past the applied commands go with the redo tail.
// undo()/redo() move through the stack and append {"cmd":"edit.undo"} / {"cmd":"edit.redo"} lines so a crash log
// replays to the same state. jump_to(n) undoes/redoes until n commands are applied (History panel click).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/commands/command.h"
#include "editor/commands/command_log.h"

namespace trispline::editor {

struct ExecutionRecord {  // one line of report.json
  std::string cmd;        // command id
  nlohmann::json line;    // the JSON line as executed
  bool ok = true;
  std::string error;        // message when !ok
  double milliseconds = 0;  // wall time of redo()
  nlohmann::json stats;     // Command::stats() after redo
  int log_line = 0;         // 1-based line in the replayed log (0 when not replayed)
};

// An action that is no undo step (anim.record), kept where it ran for the History panel and Run again.
struct HistoryOutput {
  std::size_t after = 0;  // it ran with commands [0, after) applied
  core::CommandPtr command;
  std::shared_ptr<const core::Scene> scene;  // the scene it ran on; kept only when its files were not written
};

class History {
 public:
  explicit History(core::Scene& scene);

  // Runs and records cmd; throws core::CommandError (scene unchanged) on failure.
  ExecutionRecord execute(core::CommandPtr cmd);
  bool can_undo() const { return applied_ > 0; }
  bool can_redo() const { return applied_ < commands_.size(); }
  void undo();  // no-op when nothing to undo
  void redo();  // no-op when nothing to redo
  void jump_to(std::size_t applied_count);
  // A move of the position in two parts, for a worker thread (editor/session/background_command.h). walk() takes
  // `scene` — a copy of the document — through the steps from applied() to `target` (clamped to size()): undo or redo
  // each, in order, without touching the document, the position or the log; `step(done, total)` runs before each step
  // and may throw to stop (a cancel). It throws what a step throws; `scene` is then half-way and must be dropped. While
  // it runs nothing may execute, undo, redo or clear here. settle() makes the walked `scene` the document, moves the
  // position to `target` and logs one edit.undo / edit.redo line a step, as jump_to() would.
  void walk(core::Scene& scene, std::size_t target,
            const std::function<void(std::size_t done, std::size_t total)>& step);
  void settle(core::Scene&& scene, std::size_t target);
  void clear();  // forgets the stack (the scene is not touched)
  // Takes over `other`'s stack and outputs (other is left empty), for a scene that was built by `other` and has just
  // been moved into this history's scene (Open as a transaction). Writes the stack to the log as lines that replay to
  // it: every command with the outputs in their places, then one edit.undo per command of the redo tail.
  void adopt(History& other);

  std::size_t size() const { return commands_.size(); }
  std::size_t applied() const { return applied_; }  // commands [0, applied) are in effect
  const core::Command& at(std::size_t i) const { return *commands_[i]; }
  core::Command& at(std::size_t i) { return *commands_[i]; }
  // Non-undoable commands that ran (oldest first), each after the commands applied when it ran.
  const std::vector<HistoryOutput>& outputs() const { return outputs_; }
  HistoryOutput& output(std::size_t k) { return outputs_[k]; }
  // The command the last successful execute() ran (the top of the stack, or a non-undoable one such as anim.record);
  // valid right after it, until the next execute() or clear().
  const core::Command& last_executed() const { return *last_executed_; }
  // JSON lines of the applied commands only: what Save writes.
  std::vector<nlohmann::json> applied_lines() const;

  // Optional session log: every execute/undo/redo is appended and flushed.
  void set_log(CommandLog* log) {
    log_ = log;
    log_error_reported_ = false;
  }
  // Called after every change (execute/undo/redo), e.g. to mark the viewport dirty.
  std::function<void()> on_change;
  // Called with CommandLog::error() on the first failed append to the current log (the command itself stands).
  std::function<void(const std::string&)> on_log_error;

 private:
  core::Scene& scene_;
  std::vector<core::CommandPtr> commands_;
  std::size_t applied_ = 0;
  std::vector<HistoryOutput> outputs_;            // see outputs()
  const core::Command* last_executed_ = nullptr;  // see last_executed()
  CommandLog* log_ = nullptr;
  bool log_error_reported_ = false;
  void log(const nlohmann::json& line);
  void drop_redo_tail();  // commands past applied_ and the outputs that ran after them
};

}  // namespace trispline::editor
