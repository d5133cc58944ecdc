// trispline::ui Log panel — shows a MessageLog: timestamps, errors in red, warnings in amber, auto-scroll to the
// newest message (unless the user scrolled up), a Clear button and a filter.
#pragma once

#include "ui/layout.h"
#include "ui/message_log.h"

namespace trispline::ui {

class LogPanel {
 public:
  void draw(const Rect& rect, MessageLog& log);  // Clear empties `log`

 private:
  std::size_t seen_generation_ = 0;
  bool errors_only_ = false;
  char filter_[128] = {};
};

}  // namespace trispline::ui
