// trispline::editor::WorkQueue — long synchronous work (replaying a log, loading a mesh, a placement) that must
// not freeze the UI silently: each item is first shown for one frame as "Working… <what>", then run at the
// start of the next frame. Tools reach it through ToolContext::defer. Exceptions from an item go to the Log.
#pragma once

#include <deque>
#include <functional>
#include <string>

#include "ui/message_log.h"

namespace trispline::editor {

class WorkQueue {
 public:
  void push(std::string what, std::function<void()> work);
  bool empty() const { return items_.empty(); }
  // Draws the "Working…" overlay for the front item (call while building the frame).
  void draw_overlay();
  // Runs the front item if its overlay frame has been shown. Returns true if something ran.
  bool run_ready(ui::MessageLog& messages);

 private:
  struct Item {
    std::string what;
    std::function<void()> work;
    bool shown = false;
  };
  std::deque<Item> items_;
};

}  // namespace trispline::editor
