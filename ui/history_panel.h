// trispline::ui History panel — the undo stack as a list: "(initial state)" then one row per command label;
// rows past `applied` (the redo tail) are dimmed, the current position is highlighted. Actions that are no undo step
// (anim.record) are indented rows after the command they followed. An entry whose files were not written (a log
// opened or recovered: opening never writes files) says "not written again" and has a "Run again" button.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ui/layout.h"

namespace trispline::ui {

struct HistoryOutputRow {
  std::size_t after = 0;  // shown after this many commands (0: before the first)
  std::string label;
  bool not_written = false;  // its files were not written (Run again offered)
  bool can_run_again = true;
  std::string path;  // what it writes (tooltip)
};

struct HistoryView {
  std::vector<std::string> labels;  // #commands, oldest first
  std::vector<bool> not_written;    // #commands (or empty): writes files, replayed without writing them
  std::vector<std::string> paths;   // #commands (or empty): the file a not-written command writes (tooltip)
  std::vector<HistoryOutputRow> outputs;
  std::size_t applied = 0;  // commands [0, applied) are in effect
  bool can_undo = false, can_redo = false;
};

struct HistoryPanelResult {
  std::optional<std::size_t> jump_to;           // clicked row: number of commands that should be applied
  bool undo = false, redo = false;              // the panel's arrow buttons
  std::optional<std::size_t> run_again;         // "Run again" of command i (0-based)
  std::optional<std::size_t> run_again_output;  // "Run again" of outputs[k]
};

// Row text of a command whose files were not written: "<label> — not written again".
std::string not_written_label(const std::string& label);

HistoryPanelResult draw_history_panel(const Rect& rect, const HistoryView& view);

}  // namespace trispline::ui
