// trispline::python::PyScene — the document behind trispline.Scene: a core::Scene with its editor::History, run one
// command line at a time exactly as a log line is (the builtin CommandRegistry, the same validation, History's
// finite-and-in-range guard and undo stack), and mesh.set (core/commands/mesh_set.h).
// Not copyable (the history holds a reference to the scene). The bindings lock
// mutex() after releasing the GIL, so a scene shared between Python threads is used by one at a time.
#pragma once

#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>

#include "core/commands/command.h"
#include "core/scene/scene.h"
#include "editor/commands/history.h"

namespace trispline::python {

class PyScene {
 public:
  PyScene() = default;
  PyScene(const PyScene&) = delete;
  PyScene& operator=(const PyScene&) = delete;

  // Runs one command line ({"cmd": ...} as in a log; "edit.undo" / "edit.redo" too) and returns its report entry:
  // {"line", "cmd", "ok", "ms", "stats", "command"} — report.json's per-command entry (editor/replay/replay.h), with
  // "line" the entry's number in this scene's session (1-based) and "command" the line as executed (defaults filled).
  // Relative paths resolve against ctx. Throws core::CommandError (scene unchanged).
  nlohmann::json run(const nlohmann::json& line, const core::CommandContext& ctx);
  // Executes an already parsed command (mesh.set) the same way.
  nlohmann::json execute(core::CommandPtr command);
  bool undo();  // false when there is nothing to undo
  bool redo();  // false when there is nothing to redo; throws core::CommandError when the redo fails
  // Writes the applied commands as a command log (JSON Lines), as the editor's Save does: paths relative to the
  // log's folder, written atomically. Throws std::runtime_error when the file cannot be written.
  void save(const std::filesystem::path& path) const;

  core::Scene& scene() { return scene_; }
  const core::Scene& scene() const { return scene_; }
  const editor::History& history() const { return history_; }
  std::mutex& mutex() const { return mutex_; }

 private:
  core::Scene scene_;
  editor::History history_{scene_};
  int lines_ = 0;  // entries run so far (commands, undos and redos): the next entry's "line" is lines_ + 1
  mutable std::mutex mutex_;
};

// A log line's command: any command of the builtin registry (mesh.set included). Throws core::CommandError
// naming the field ("cmd" for an unknown command).
core::CommandPtr parse_command(const nlohmann::json& line, const core::CommandContext& ctx);

}  // namespace trispline::python
