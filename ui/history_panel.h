// trispline::ui History panel — the undo stack as a list: "(initial state)" then one row per command label;
// rows past `applied` (the redo tail) are dimmed, the current position is highlighted.
#pragma once

#include "ui/layout.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace trispline::ui {

struct HistoryView {
  std::vector<std::string> labels;  // #commands, oldest first
  std::size_t applied = 0;          // commands [0, applied) are in effect
  bool can_undo = false, can_redo = false;
};

struct HistoryPanelResult {
  std::optional<std::size_t> jump_to;  // clicked row: number of commands that should be applied
  bool undo = false, redo = false;     // the panel's arrow buttons
};

HistoryPanelResult draw_history_panel(const Rect& rect, const HistoryView& view);

}  // namespace trispline::ui
