// trispline::editor::EditorSession — the interactive editor's document: the scene, its undo history, the
// session command log with its lock (crash recovery), and Open / Save / New. Every error is reported to the
// Log panel's MessageLog; no member throws.
//
// Session files live in state_dir() (TRISPLINE_STATE_DIR, else $XDG_STATE_HOME/trispline, else
// ~/.local/state/trispline):
//   session.jsonl            every executed / undone / redone command of this run, flushed at once (History log)
//   session.prev.jsonl       the log of the document before the last New / Open / recovery (renamed aside)
//   session.lock             exists while an editor runs (holds its pid); removed on clean exit
//   session.recovered.jsonl  the previous unfinished session's log, moved aside at start (the readable prefix);
//                            session.recovered-N.jsonl when an unanswered offer still holds that name
//   session.recover-pending  the recovery question is open (asked again if this run dies before answering);
//                            holds the file name of the log on offer
// A lock whose pid is still alive belongs to another running editor: this one then uses session-<pid>.* files.
// If the unfinished log cannot be moved aside, it is left untouched (with its lock) and this run logs to
// session-<pid>.jsonl. A session-<pid>.lock whose pid is dead (a crashed second editor) is offered for recovery
// like session.lock.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "core/scene/scene.h"
#include "editor/commands/command_log.h"
#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "ui/history_panel.h"
#include "ui/main_menu.h"
#include "ui/message_log.h"
#include "ui/status_bar.h"

namespace trispline::editor {

std::filesystem::path state_dir();  // see above; not created

// A previous session that did not end cleanly and left commands behind.
struct RecoveryOffer {
  std::filesystem::path log;  // session.recovered.jsonl
  std::size_t commands = 0;   // lines in it (edit.undo / edit.redo included)
};

// The Log's text of a failed command: "ddm.fill: field 'tile': <message>" (the field named once).
std::string command_error_text(const std::string& id, const core::CommandError& e);

// A camera.set log line for `camera` (eye, target, up, fov_deg, viewport).
nlohmann::json camera_line(const core::Camera& camera);

class EditorSession {
 public:
  explicit EditorSession(ui::MessageLog& messages);
  ~EditorSession();  // closes the log; the lock stays unless finish() ran (so a crash is detected next time)
  EditorSession(const EditorSession&) = delete;
  EditorSession& operator=(const EditorSession&) = delete;

  // Opens the session log and lock. With check_previous, an unfinished previous session is moved aside and
  // returned as an offer (without it, it is still moved aside, and the Log says where).
  std::optional<RecoveryOffer> start(bool check_previous);
  void finish();  // clean exit: closes the log and removes the lock

  // Parses `line` with the command registry and executes it (relative paths against base_dir, default: the
  // current folder; files the command writes under output_dir, default: base_dir — the folder the user chose in a
  // dialog). Errors go to the Log in red; the scene is then unchanged. Returns success.
  bool execute(const nlohmann::json& line, const std::filesystem::path& base_dir = {},
               const std::filesystem::path& output_dir = {});
  // Executes a parsed command (prepared or not: Command::prepare) like execute(line); the Log's time adds
  // `prepared_ms`, the time its preparation took elsewhere. Returns success.
  bool execute(core::CommandPtr cmd, double prepared_ms = 0.0);
  bool undo();
  bool redo();
  bool jump_to(std::size_t applied_count);
  // The UI thread's end of a move of the history walked on a worker (History::walk,
  // editor/session/background_command.h): `scene` becomes the document at position `target`; the Log says what moved
  // ("Undo X", "Redo X", "History: N steps back"). Returns success.
  bool settle_history(core::Scene&& scene, std::size_t target);
  // History's "Run again" of command i, a core::FileOutput replayed without writing (Open, recovery): writes its files
  // from the result it kept (the scene as it was at that step), no new history step. Errors go to the Log.
  bool run_again(std::size_t i);
  // The same for outputs()[k] whose command writes itself; anim.record is recorded by AnimationUi::record_again.
  bool run_again_output(std::size_t k);

  // Empty scene and history; restarts the session log (the old one is renamed to <log>.prev.jsonl, not lost).
  void new_document();  // refused while busy(), like every change below
  // A transaction: replays the log into a fresh scene (each line one undoable step) and swaps it in only when every
  // line succeeded; it writes no file (FileWrites::skip: volume.export, anim.record are History entries "not written
  // again", with Run again); otherwise the error (LOG:LINE: ...) goes to the Log and the current scene, history, title
  // and session log are kept as they were. On success the session log restarts with the opened history.
  bool open(const std::filesystem::path& log);
  // open() in two parts, for a worker thread (editor/session/background_command.h): prepare_open() replays `log` into a
  // scene and history of their own and touches nothing of the session (`on_executed` runs after each line: progress,
  // and a throw there stops the replay); commit_open() is open()'s second half on the UI thread — the document becomes
  // the replayed one when every line succeeded, else the Log says why and nothing changes. Returns success.
  struct OpenedLog {
    std::filesystem::path log;
    core::Scene scene;
    History history{scene};
    ReplayResult result;
    bool missing = false;  // no such file
  };
  static std::unique_ptr<OpenedLog> prepare_open(const std::filesystem::path& log, const ReplayHook& on_executed = {});
  bool commit_open(std::unique_ptr<OpenedLog> opened);
  bool save(const std::filesystem::path& path, const core::Camera& view);  // applied lines + camera.set, atomic
  // new_document() + replay of the offer's log (writing no file, like open()); then closes the question.
  bool recover(const RecoveryOffer& offer);
  void discard(const RecoveryOffer& offer);  // keeps the file, says so

  // While a command is prepared on a worker thread over a copy of the scene (editor/session/background_command.h) the
  // document must stay as that copy: `what` ("Filling teapot with thorn") makes execute, undo, redo, jump_to,
  // new_document, open and recover refuse with a Log warning naming it (nothing is queued). Empty: not busy.
  // history_view() answers from a copy taken when the session became busy: a worker may be walking the history's
  // commands (BackgroundCommand::start_history), and a label can read what a redo writes (a press's limit).
  void set_busy(std::string what);
  const std::string& busy() const { return busy_; }

  core::Scene& scene() { return scene_; }
  const core::Scene& scene() const { return scene_; }
  History& history() { return history_; }
  const History& history() const { return history_; }
  ui::MessageLog& messages() { return messages_; }
  bool has_command(const std::string& id) const;  // registered in the command registry

  const std::filesystem::path& document() const { return document_; }  // last opened/saved log ("" = untitled)
  bool modified() const;
  double last_ms() const { return last_ms_; }  // wall time of the last execute, < 0 = none
  const std::string& last_label() const { return last_label_; }
  std::uint64_t change_count() const { return changes_; }  // bumped on every history change
  ui::StatusInfo status() const;         // for the status bar (document, counts, last command; no hint)
  ui::HistoryView history_view() const;  // for the History panel (the copy taken by set_busy while busy)
  ui::MenuState menu_state() const;      // undo/redo availability and labels for the Edit menu

 private:
  bool step_history(bool forward);  // undo (false) or redo (true) one step, reported in the Log
  bool replay_into(const std::filesystem::path& log, const char* what);
  // A previous run died leaving `log`: copy its readable prefix aside, maybe offer it. *kept is false if the copy
  // could not be written (then `log` must be left alone).
  std::optional<RecoveryOffer> keep_unfinished(bool ask, const std::filesystem::path& log, bool* kept);
  std::optional<RecoveryOffer> keep_dead_instances(bool ask);  // session-<pid>.lock files whose pid is dead
  std::filesystem::path pending_log() const;                   // the log the open recovery question is about
  void open_session_log(bool keep_old);                        // keep_old: rename the current log aside first
  std::pair<std::size_t, const core::Command*> marker() const;
  bool refused(const char* change) const;  // busy(): says so in the Log and returns true

  ui::MessageLog& messages_;
  core::Scene scene_;
  History history_;
  std::unique_ptr<CommandLog> log_;
  std::filesystem::path dir_, log_path_, lock_path_;
  std::filesystem::path document_;
  std::pair<std::size_t, const core::Command*> saved_{0, nullptr};
  double last_ms_ = -1;
  std::string last_label_;
  std::uint64_t changes_ = 0;
  std::string busy_;
  ui::HistoryView busy_view_;  // history_view() while busy (set_busy)
};

}  // namespace trispline::editor
