// trispline::ui Tool panel — the docked window holding the tool selector (one toggle button per tool) and, below
// it, the active tool's own parameters (drawn by the tool between begin_tool_panel() and end_tool_panel()).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "ui/layout.h"

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

// The "Control point" section for a deformed object (drawn in the Tool panel under the tool's parameters): i/j/k
// steppers choose a control point P_ijk of its lattice, a drag field edits its position (world units). One edit =
// one lattice.set_point line, returned when the field is released (IsItemDeactivatedAfterEdit), so every precise
// edit is one undoable command.
struct ControlPointState {
  int index[3] = {0, 0, 0};
  double position[3] = {0, 0, 0};  // edit buffer; re-read from the lattice whenever it is not being dragged
  std::string object;              // the object the index refers to (reset to 0,0,0 on another object)
  bool highlight = false;          // the section is hovered or edited: the editor marks P_ijk in the viewport
};
std::optional<nlohmann::json> draw_control_point_section(const core::SceneObject& object, ControlPointState& state);

// {"cmd":"lattice.set_point","object":ID,"index":[i,j,k],"position":[x,y,z]}.
nlohmann::json set_point_line(const std::string& object, const int index[3], const double position[3]);

}  // namespace trispline::ui
