// trispline::ui::MessageLog — the messages shown in the Log panel (info / warning / error, with wall-clock
// timestamps). Plain data, no ImGui: the editor appends to it, ui::draw_log_panel() shows it.
#pragma once

#include <cstddef>
#include <deque>
#include <string>

namespace trispline::ui {

enum class Severity { Info, Warning, Error };

struct Message {
  Severity severity = Severity::Info;
  std::string time;  // "HH:MM:SS" local time when added
  std::string text;
};

class MessageLog {
 public:
  explicit MessageLog(std::size_t capacity = 2000) : capacity_(capacity) {}
  void add(Severity severity, std::string text);  // also echoed to stderr for warnings and errors
  void info(std::string text) { add(Severity::Info, std::move(text)); }
  void warning(std::string text) { add(Severity::Warning, std::move(text)); }
  void error(std::string text) { add(Severity::Error, std::move(text)); }
  void clear() { messages_.clear(); }

  const std::deque<Message>& messages() const { return messages_; }
  std::size_t error_count() const { return errors_; }  // errors since start (not reset by clear)
  // Incremented on every add(); the panel scrolls to the bottom when it changes.
  std::size_t generation() const { return generation_; }

 private:
  std::size_t capacity_;
  std::deque<Message> messages_;
  std::size_t errors_ = 0;
  std::size_t generation_ = 0;
};

}  // namespace trispline::ui
