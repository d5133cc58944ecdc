#include "editor/history.h"

#include <chrono>

namespace trispline::editor {

History::History(core::Scene& scene) : scene_(scene) {}

ExecutionRecord History::execute(core::CommandPtr cmd) {
  ExecutionRecord rec;
  rec.cmd = cmd->id();
  const auto t0 = std::chrono::steady_clock::now();
  cmd->redo(scene_);  // throws CommandError with the scene unchanged
  rec.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  rec.line = cmd->to_json();
  rec.stats = cmd->stats();
  if (!cmd->undoable()) {  // logged for replays; the undo stack and its redo tail stay as they are
    log(rec.line);
    return rec;
  }
  commands_.resize(applied_);
  commands_.push_back(std::move(cmd));
  applied_ = commands_.size();
  log(rec.line);
  if (on_change) on_change();
  return rec;
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

void History::clear() {
  commands_.clear();
  applied_ = 0;
  if (on_change) on_change();
}

std::vector<nlohmann::json> History::applied_lines() const {
  std::vector<nlohmann::json> lines;
  for (std::size_t i = 0; i < applied_; ++i) lines.push_back(commands_[i]->to_json());
  return lines;
}

}  // namespace trispline::editor
