#include "editor/tools/work_queue.h"

#include "ui/overlays.h"

namespace trispline::editor {

void WorkQueue::push(std::string what, std::function<void()> work) {
  items_.push_back({std::move(what), std::move(work), false});
}

void WorkQueue::draw_overlay() {
  if (items_.empty()) return;
  ui::draw_working_overlay("Working... " + items_.front().what);
  items_.front().shown = true;
}

bool WorkQueue::run_ready(ui::MessageLog& messages) {
  if (items_.empty() || !items_.front().shown) return false;
  Item item = std::move(items_.front());
  items_.pop_front();
  try {
    item.work();
  } catch (const std::exception& e) {
    messages.error(item.what + " failed: " + e.what());
  }
  return true;
}

}  // namespace trispline::editor
