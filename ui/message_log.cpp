#include "ui/message_log.h"

#include <chrono>
#include <ctime>
#include <iostream>

namespace trispline::ui {

void MessageLog::add(Severity severity, std::string text) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[16];
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", &local);
  if (severity != Severity::Info)
    std::cerr << "trispline: " << (severity == Severity::Error ? "error: " : "warning: ") << text << '\n';
  if (severity == Severity::Error) ++errors_;
  messages_.push_back({severity, stamp, std::move(text)});
  while (messages_.size() > capacity_) messages_.pop_front();
  ++generation_;
}

}  // namespace trispline::ui
