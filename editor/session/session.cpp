#include "editor/session/session.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "core/commands/camera_set.h"
#include "core/commands/file_output.h"
#include "editor/commands/command_registry.h"
#include "editor/replay/replay.h"

namespace fs = std::filesystem;

namespace trispline::editor {

namespace {

bool process_alive(long pid) {
  if (pid <= 0) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

// Reads the parseable prefix of a (possibly crash-truncated) log: JSON-object lines up to the first bad one.
std::vector<nlohmann::json> readable_prefix(const fs::path& path, bool* truncated) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  std::string text;
  *truncated = false;
  while (std::getline(in, text)) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      *truncated = true;
      break;
    }
    lines.push_back(std::move(j));
  }
  return lines;
}

}  // namespace

fs::path state_dir() {
  if (const char* d = std::getenv("TRISPLINE_STATE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && *x) return fs::path(x) / "trispline";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".local" / "state" / "trispline";
  return fs::temp_directory_path() / "trispline-state";
}

nlohmann::json camera_line(const core::Camera& c) { return core::CameraSetCommand::schema().to_json(c); }

EditorSession::EditorSession(ui::MessageLog& messages) : messages_(messages), history_(scene_) {
  history_.on_change = [this] { ++changes_; };
  history_.on_log_error = [this](const std::string& error) {
    messages_.warning("session log: " + error + "; crash recovery may miss the commands from here on");
  };
}

EditorSession::~EditorSession() {
  history_.set_log(nullptr);
  log_.reset();
}

std::optional<RecoveryOffer> EditorSession::start(bool check_previous) {
  std::optional<RecoveryOffer> offer;
  std::error_code ec;
  dir_ = state_dir();
  fs::create_directories(dir_, ec);
  if (ec) {
    messages_.warning("no session log (crash recovery off): cannot create " + dir_.string() + ": " + ec.message());
    return offer;
  }
  const std::string own = "session-" + std::to_string(::getpid());
  log_path_ = dir_ / "session.jsonl";
  lock_path_ = dir_ / "session.lock";
  if (fs::exists(lock_path_)) {
    long pid = 0;
    std::ifstream(lock_path_) >> pid;
    if (pid != long(::getpid()) && process_alive(pid)) {
      messages_.warning("another trispline editor (pid " + std::to_string(pid) + ") uses " + log_path_.string() +
                        "; this one logs to " + own + ".jsonl");
      log_path_ = dir_ / (own + ".jsonl");
      lock_path_ = dir_ / (own + ".lock");
    } else {
      bool kept = true;
      offer = keep_unfinished(check_previous, log_path_, &kept);
      if (!kept) {  // the only copy of that log: leave it (and its lock, so the next start tries again)
        messages_.warning("the unfinished session's log is left in " + log_path_.string() + "; this editor logs to " +
                          own + ".jsonl");
        log_path_ = dir_ / (own + ".jsonl");
        lock_path_ = dir_ / (own + ".lock");
      }
    }
  }
  if (!offer) offer = keep_dead_instances(check_previous);
  open_session_log(false);
  std::ofstream(lock_path_, std::ios::trunc) << ::getpid() << '\n';
  return offer;
}

std::optional<RecoveryOffer> EditorSession::keep_dead_instances(bool ask) {
  std::error_code ec;
  std::vector<std::pair<long, fs::path>> locks;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string prefix = "session-", suffix = ".lock";
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    locks.emplace_back(std::stol(digits), it->path());
  }
  std::sort(locks.begin(), locks.end());
  for (const auto& [pid, lock] : locks) {
    if (pid == long(::getpid()) || process_alive(pid)) continue;
    const fs::path log = dir_ / ("session-" + std::to_string(pid) + ".jsonl");
    bool kept = true;
    std::optional<RecoveryOffer> offer = keep_unfinished(ask, log, &kept);
    if (!kept) continue;  // left as it is for the next start
    fs::remove(log, ec);
    fs::remove(lock, ec);
    if (offer) return offer;
  }
  return std::nullopt;
}

fs::path EditorSession::pending_log() const {
  std::string name;
  std::getline(std::ifstream(dir_ / "session.recover-pending"), name);
  if (name.empty() || name == "asked" || name.find('/') != std::string::npos) name = "session.recovered.jsonl";
  return dir_ / name;
}

std::optional<RecoveryOffer> EditorSession::keep_unfinished(bool ask, const fs::path& log, bool* kept) {
  const fs::path pending = dir_ / "session.recover-pending";
  fs::path aside = dir_ / "session.recovered.jsonl";
  std::error_code ec;
  bool truncated = false;
  *kept = true;
  std::vector<nlohmann::json> lines;
  if (fs::file_size(log, ec) > 0 && !ec) lines = readable_prefix(log, &truncated);
  if (!lines.empty()) {
    if (fs::exists(pending, ec))  // an unanswered offer: never overwrite its log (nor any other kept one)
      for (int n = 1; fs::exists(aside, ec) || aside == pending_log(); ++n)
        aside = dir_ / ("session.recovered-" + std::to_string(n) + ".jsonl");
    try {
      write_log_atomic(aside, lines);
    } catch (const std::exception& e) {
      messages_.error(std::string("cannot keep the unfinished session's log: ") + e.what());
      *kept = false;
      return std::nullopt;
    }
    std::ofstream(pending, std::ios::trunc) << aside.filename().string() << '\n';
    if (truncated) messages_.warning("the unfinished session's log ends with a damaged line; it was dropped");
  } else if (fs::exists(pending, ec)) {  // the run that was asked died before answering: ask again
    aside = pending_log();
    lines = readable_prefix(aside, &truncated);
  }
  if (lines.empty()) return std::nullopt;
  if (ask) return RecoveryOffer{aside, lines.size()};
  fs::remove(pending, ec);
  messages_.info("unfinished previous session kept in " + aside.string());
  return std::nullopt;
}

void EditorSession::open_session_log(bool keep_old) {
  if (log_path_.empty()) return;
  history_.set_log(nullptr);
  log_.reset();
  std::error_code ec;
  if (keep_old && fs::file_size(log_path_, ec) > 0 && !ec) {
    const fs::path prev = log_path_.parent_path() / (log_path_.stem().string() + ".prev.jsonl");
    fs::rename(log_path_, prev, ec);
    if (ec)
      messages_.warning("cannot keep the old session log as " + prev.string() + ": " + ec.message() +
                        "; it is restarted");
  }
  try {
    log_ = std::make_unique<CommandLog>(log_path_, true);
    history_.set_log(log_.get());
  } catch (const std::exception& e) {
    messages_.warning(std::string("no session log (crash recovery off): ") + e.what());
  }
}

void EditorSession::finish() {
  history_.set_log(nullptr);
  log_.reset();
  std::error_code ec;
  if (!lock_path_.empty()) fs::remove(lock_path_, ec);
}

bool EditorSession::has_command(const std::string& id) const {
  for (const std::string& known : CommandRegistry::builtin().ids())
    if (known == id) return true;
  return false;
}

std::string command_error_text(const std::string& id, const core::CommandError& e) {
  const std::string what = e.what(), field = "field '" + e.field() + "'";
  const bool named = e.field().empty() || what.find(field) != std::string::npos;  // message names it already
  return id + ": " + (named ? "" : field + ": ") + what;
}

bool EditorSession::refused(const char* change) const {
  if (busy_.empty()) return false;
  messages_.warning(std::string(change) + " refused: " + busy_ + " (wait for it or cancel it)");
  return true;
}

bool EditorSession::execute(const nlohmann::json& line, const fs::path& base_dir, const fs::path& output_dir) {
  const std::string id = line.contains("cmd") && line["cmd"].is_string() ? line["cmd"].get<std::string>() : "?";
  if (refused(id.c_str())) return false;
  try {
    core::CommandContext ctx;
    std::error_code ec;
    ctx.base_dir = base_dir.empty() ? fs::current_path(ec) : base_dir;
    ctx.output_dir = output_dir;
    return execute(CommandRegistry::builtin().parse(line, ctx));
  } catch (const core::CommandError& e) {
    messages_.error(command_error_text(id, e));
  } catch (const std::exception& e) {
    messages_.error(std::string("command failed: ") + e.what());
  }
  return false;
}

bool EditorSession::execute(core::CommandPtr cmd, double prepared_ms) {
  const std::string id = cmd->id();
  if (refused(id.c_str())) return false;
  try {
    const ExecutionRecord rec = history_.execute(std::move(cmd));
    const std::string label = history_.last_executed().label();
    last_ms_ = prepared_ms + rec.milliseconds;
    last_label_ = label;
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", last_ms_);
    messages_.info(label + " (" + ms + " ms)");
    return true;
  } catch (const core::CommandError& e) {
    messages_.error(command_error_text(id, e));
  } catch (const std::exception& e) {
    messages_.error(std::string("command failed: ") + e.what());
  }
  return false;
}

bool EditorSession::undo() { return step_history(false); }
bool EditorSession::redo() { return step_history(true); }

bool EditorSession::step_history(bool forward) {
  if (forward ? !history_.can_redo() : !history_.can_undo()) return false;
  if (refused(forward ? "Redo" : "Undo")) return false;
  const char* verb = forward ? "Redo" : "Undo";
  try {
    const std::string label = history_.at(forward ? history_.applied() : history_.applied() - 1).label();
    forward ? history_.redo() : history_.undo();
    messages_.info(std::string(verb) + " " + label);
    return true;
  } catch (const std::exception& e) {
    messages_.error(std::string(forward ? "redo" : "undo") + " failed: " + e.what());
  }
  return false;
}

bool EditorSession::settle_history(core::Scene&& scene, std::size_t target) {
  const std::size_t from = history_.applied();
  target = std::min(target, history_.size());
  std::string what;
  if (target + 1 == from)
    what = "Undo " + history_.at(target).label();
  else if (target == from + 1)
    what = "Redo " + history_.at(from).label();
  else
    what = "History: " + std::to_string(target > from ? target - from : from - target) + " steps " +
           (target > from ? "forward" : "back");
  history_.settle(std::move(scene), target);
  messages_.info(what);
  return true;
}

bool EditorSession::jump_to(std::size_t applied_count) {
  if (refused("History jump")) return false;
  try {
    history_.jump_to(applied_count);
    return true;
  } catch (const std::exception& e) {
    messages_.error(std::string("history jump failed: ") + e.what());
  }
  return false;
}

namespace {

// Writes `command`'s files (a FileOutput that writes itself and has not written them); the Log says what happened.
bool write_again(core::Command& command, ui::MessageLog& messages) {
  core::FileOutput* out = core::file_output(command);
  if (!out || !out->writes_itself()) {
    messages.warning(command.label() + ": nothing to run again here");
    return false;
  }
  try {
    out->write_files();
    messages.info(command.label() + ": wrote " + out->output_path().string());
    return true;
  } catch (const core::CommandError& e) {
    messages.error(command_error_text(command.id(), e));
  } catch (const std::exception& e) {
    messages.error(command.label() + ": " + e.what());
  }
  return false;
}

}  // namespace

bool EditorSession::run_again(std::size_t i) {
  if (i >= history_.size() || refused("Run again")) return false;
  const bool ok = write_again(history_.at(i), messages_);
  if (ok) ++changes_;
  return ok;
}

bool EditorSession::run_again_output(std::size_t k) {
  if (k >= history_.outputs().size() || refused("Run again")) return false;
  const bool ok = write_again(*history_.output(k).command, messages_);
  if (ok) {
    history_.output(k).scene.reset();
    ++changes_;
  }
  return ok;
}

void EditorSession::new_document() {
  if (refused("New")) return;
  history_.clear();
  scene_.clear();
  scene_.camera_set = false;
  document_.clear();
  last_ms_ = -1;
  last_label_.clear();
  open_session_log(true);  // the old lines no longer replay to this document: renamed aside
  saved_ = marker();
  ++changes_;
}

bool EditorSession::replay_into(const fs::path& log, const char* what) {
  new_document();
  const ReplayResult r = replay_lines(history_, log, {}, {}, FileWrites::skip);
  std::size_t ok = 0;
  double ms = 0;
  for (const ExecutionRecord& rec : r.records) {
    if (rec.ok) ++ok;
    ms += rec.milliseconds;
  }
  char line[256];
  std::snprintf(line, sizeof line, "%s %s: %zu command%s in %.0f ms", what, log.filename().string().c_str(), ok,
                ok == 1 ? "" : "s", ms);
  messages_.info(line);
  if (!r.ok) messages_.error(r.error);
  last_ms_ = ms;
  last_label_ = std::string(what) + " " + log.filename().string();
  return r.ok;
}

bool EditorSession::open(const fs::path& log) {
  if (refused("Open")) return false;
  return commit_open(prepare_open(log));
}

std::unique_ptr<EditorSession::OpenedLog> EditorSession::prepare_open(const fs::path& log,
                                                                      const ReplayHook& on_executed) {
  // A transaction: the log is replayed into a scene of its own, which replaces the document only when every line
  // succeeded. Otherwise the current scene, its history, its title and its session log stay as they were.
  auto opened = std::make_unique<OpenedLog>();
  opened->log = log;
  ReplayResult& r = opened->result;
  std::error_code ec;
  if (!fs::exists(log, ec)) {
    r.ok = false;
    opened->missing = true;
    return opened;
  }
  try {
    r = replay_lines(opened->history, log, on_executed, {}, FileWrites::skip);  // opening never writes files
  } catch (const std::exception& e) {  // replay_lines reports line errors itself; this is memory and the like
    r.ok = false;
    r.error = log.string() + ": " + e.what();
  }
  return opened;
}

bool EditorSession::commit_open(std::unique_ptr<OpenedLog> opened) {
  const fs::path& log = opened->log;
  const ReplayResult& r = opened->result;
  std::error_code ec;
  core::Scene& fresh = opened->scene;
  History& fresh_history = opened->history;
  if (opened->missing) {
    messages_.error("cannot open " + log.string() + ": no such file");
    return false;
  }
  if (!r.ok) {
    messages_.error("Open failed, the current scene is kept: " + r.error);
    return false;
  }
  std::size_t ok = 0;
  double ms = 0;
  for (const ExecutionRecord& rec : r.records) {
    ok += rec.ok;
    ms += rec.milliseconds;
  }
  history_.clear();
  scene_ = std::move(fresh);
  last_ms_ = ms;
  last_label_ = "Opened " + log.filename().string();
  open_session_log(true);  // the old document's lines are renamed aside, the new log gets the opened history
  history_.adopt(fresh_history);
  document_ = fs::absolute(log, ec).lexically_normal();
  saved_ = marker();
  ++changes_;
  char line[256];
  std::snprintf(line, sizeof line, "Opened %s: %zu command%s in %.0f ms", log.filename().string().c_str(), ok,
                ok == 1 ? "" : "s", ms);
  messages_.info(line);
  return true;
}

bool EditorSession::save(const fs::path& path, const core::Camera& view) {
  try {
    std::vector<nlohmann::json> lines = history_.applied_lines();
    lines.push_back(camera_line(view));
    make_paths_relative(lines, fs::absolute(path).parent_path());
    write_log_atomic(path, lines);
    document_ = path;
    saved_ = marker();
    messages_.info("Saved " + path.string() + " (" + std::to_string(lines.size()) + " lines)");
    return true;
  } catch (const std::exception& e) {
    messages_.error("cannot save " + path.string() + ": " + e.what());
  }
  return false;
}

bool EditorSession::recover(const RecoveryOffer& offer) {
  if (refused("Recover")) return false;
  const bool ok = replay_into(offer.log, "Recovered");
  std::error_code ec;  // answered only now: a crash during the replay asks again
  fs::remove(dir_ / "session.recover-pending", ec);
  return ok;
}

void EditorSession::discard(const RecoveryOffer& offer) {
  std::error_code ec;
  fs::remove(dir_ / "session.recover-pending", ec);
  messages_.info("previous session discarded (its log is kept in " + offer.log.string() + ")");
}

std::pair<std::size_t, const core::Command*> EditorSession::marker() const {
  const std::size_t n = history_.applied();
  return {n, n > 0 ? &history_.at(n - 1) : nullptr};
}

bool EditorSession::modified() const { return marker() != saved_; }

ui::StatusInfo EditorSession::status() const {
  ui::StatusInfo st;
  st.document = document_.empty() ? "untitled" : document_.filename().string();
  st.modified = modified();
  for (const core::SceneObject& o : scene_.objects()) {
    ++st.objects;
    if (!o.world_mesh) continue;
    st.vertices += o.world_mesh->vertex_count();
    st.triangles += o.world_mesh->triangle_count();
  }
  st.last_command = last_label_;
  st.last_command_ms = last_ms_;
  return st;
}

ui::MenuState EditorSession::menu_state() const {
  ui::MenuState m;
  m.can_undo = history_.can_undo() && busy_.empty();
  m.can_redo = history_.can_redo() && busy_.empty();
  if (m.can_undo) m.undo_label = history_.at(history_.applied() - 1).label();
  if (m.can_redo) m.redo_label = history_.at(history_.applied()).label();
  m.has_document_path = !document_.empty();
  return m;
}

void EditorSession::set_busy(std::string what) {
  if (!what.empty() && busy_.empty()) busy_view_ = history_view();
  busy_ = std::move(what);
}

ui::HistoryView EditorSession::history_view() const {
  if (!busy_.empty()) {
    ui::HistoryView v = busy_view_;
    v.can_undo = v.can_redo = false;  // nothing moves while busy
    return v;
  }
  ui::HistoryView v;
  v.applied = history_.applied();
  v.can_undo = history_.can_undo();
  v.can_redo = history_.can_redo();
  for (std::size_t i = 0; i < history_.size(); ++i) {
    v.labels.push_back(history_.at(i).label());
    const core::FileOutput* out = core::file_output(history_.at(i));
    v.not_written.push_back(out && !out->files_written());
    v.paths.push_back(out ? out->output_path().string() : std::string());
  }
  for (const HistoryOutput& o : history_.outputs()) {
    ui::HistoryOutputRow row;
    row.after = o.after;
    row.label = o.command->label();
    const core::FileOutput* out = core::file_output(*o.command);
    row.not_written = out && !out->files_written();
    row.can_run_again = out && (out->writes_itself() || o.scene);
    row.path = out ? out->output_path().string() : std::string();
    v.outputs.push_back(std::move(row));
  }
  return v;
}

}  // namespace trispline::editor
