#include "editor/commands/history.h"

#include <algorithm>
#include <chrono>

#include "core/commands/file_output.h"
#include "core/scene/scene_check.h"

namespace trispline::editor {

History::History(core::Scene& scene) : scene_(scene) {}

ExecutionRecord History::execute(core::CommandPtr cmd) {
  ExecutionRecord rec;
  rec.cmd = cmd->id();
  const auto t0 = std::chrono::steady_clock::now();
  const core::SceneGuard guard(scene_);
  cmd->redo(scene_);  // throws CommandError with the scene unchanged
  // Every command's result must be finite and in range (core/scene/scene_check.h); one that is not is taken back.
  if (const std::string bad = guard.error(scene_); !bad.empty()) {
    cmd->undo(scene_);
    throw core::CommandError("the result is not finite or out of range, nothing changed: " + bad);
  }
  rec.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  rec.line = cmd->to_json();
  rec.stats = cmd->stats();
  if (!cmd->undoable()) {  // logged for replays; the undo stack and its redo tail stay as they are
    HistoryOutput out;
    out.after = applied_;
    if (const core::FileOutput* f = core::file_output(*cmd); f && !f->files_written())
      out.scene = std::make_shared<const core::Scene>(scene_);  // shallow: meshes and tables are shared pointers
    out.command = std::move(cmd);
    outputs_.push_back(std::move(out));
    last_executed_ = outputs_.back().command.get();
    log(rec.line);
    if (on_change) on_change();
    return rec;
  }
  drop_redo_tail();
  commands_.push_back(std::move(cmd));
  applied_ = commands_.size();
  last_executed_ = commands_.back().get();
  log(rec.line);
  if (on_change) on_change();
  return rec;
}

void History::drop_redo_tail() {
  commands_.resize(applied_);
  std::erase_if(outputs_, [this](const HistoryOutput& o) { return o.after > applied_; });
}

void History::undo() {
  if (!can_undo()) return;
  commands_[applied_ - 1]->undo(scene_);
  --applied_;
  log({{"cmd", "edit.undo"}});
  if (on_change) on_change();
}

void History::redo() {
  if (!can_redo()) return;
  commands_[applied_]->redo(scene_);  // may throw (CommandError): then nothing moved
  ++applied_;
  log({{"cmd", "edit.redo"}});
  if (on_change) on_change();
}

void History::log(const nlohmann::json& line) {
  if (!log_ || log_->append(line) || log_error_reported_) return;
  log_error_reported_ = true;
  if (on_log_error) on_log_error(log_->error());
}

void History::jump_to(std::size_t applied_count) {
  if (applied_count > commands_.size()) applied_count = commands_.size();
  while (applied_ > applied_count) undo();
  while (applied_ < applied_count) redo();
}

void History::walk(core::Scene& scene, std::size_t target, const std::function<void(std::size_t, std::size_t)>& step) {
  target = std::min(target, commands_.size());
  const std::size_t total = target > applied_ ? target - applied_ : applied_ - target;
  std::size_t done = 0;
  for (std::size_t a = applied_; a > target; --a) {
    step(done++, total);
    commands_[a - 1]->undo(scene);
  }
  for (std::size_t a = applied_; a < target; ++a) {
    step(done++, total);
    commands_[a]->redo(scene);
  }
}

void History::settle(core::Scene&& scene, std::size_t target) {
  target = std::min(target, commands_.size());
  scene_ = std::move(scene);
  for (; applied_ > target; --applied_) log({{"cmd", "edit.undo"}});
  for (; applied_ < target; ++applied_) log({{"cmd", "edit.redo"}});
  if (on_change) on_change();
}

void History::adopt(History& other) {
  commands_ = std::move(other.commands_);
  applied_ = other.applied_;
  outputs_ = std::move(other.outputs_);
  last_executed_ = other.last_executed_;  // owned by commands_ or outputs_ now
  other.commands_.clear();
  other.outputs_.clear();
  other.applied_ = 0;
  other.last_executed_ = nullptr;
  std::stable_sort(outputs_.begin(), outputs_.end(),  // by place (one may have run after an undo)
                   [](const HistoryOutput& a, const HistoryOutput& b) { return a.after < b.after; });
  std::size_t next_output = 0;
  for (std::size_t i = 0; i <= commands_.size(); ++i) {
    for (; next_output < outputs_.size() && outputs_[next_output].after == i; ++next_output)
      log(outputs_[next_output].command->to_json());
    if (i < commands_.size()) log(commands_[i]->to_json());
  }
  for (std::size_t i = applied_; i < commands_.size(); ++i) log({{"cmd", "edit.undo"}});
  if (on_change) on_change();
}

void History::clear() {
  commands_.clear();
  outputs_.clear();
  last_executed_ = nullptr;
  applied_ = 0;
  if (on_change) on_change();
}

std::vector<nlohmann::json> History::applied_lines() const {
  std::vector<nlohmann::json> lines;
  for (std::size_t i = 0; i < applied_; ++i) lines.push_back(commands_[i]->to_json());
  return lines;
}

}  // namespace trispline::editor
