// trispline::ui Tool panel — the docked window holding the tool selector (one toggle button per tool) and, below
// it, the active tool's own parameters (drawn by the tool between begin_tool_panel() and end_tool_panel()).
#pragma once

#include "ui/layout.h"

#include <string>
#include <vector>

namespace trispline::ui {

struct ToolEntry {
  std::string name;      // "Select", "Sketch placement"
  std::string shortcut;  // "Q"
  std::string tooltip;
};

// Begins the window and draws the selector; `active` is updated on click. Always call end_tool_panel().
// Returns false when the window is collapsed/clipped (skip drawing parameters then).
bool begin_tool_panel(const Rect& rect, const std::vector<ToolEntry>& tools, int* active);
void end_tool_panel();

}  // namespace trispline::ui
