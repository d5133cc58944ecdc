// trispline::editor::Toolbox — the editor's tools (Select, Sketch placement, Press, …), which one is active, and the
// plumbing every tool shares: the Tool panel (selector + the active tool's parameters), mouse input over the
// viewport, view decorations and the status-bar hint.
#pragma once

#include <memory>
#include <vector>

#include "editor/tools/tool.h"
#include "ui/layout.h"

namespace trispline::editor {

class Toolbox {
 public:
  explicit Toolbox(ToolContext& ctx);  // ctx must outlive the toolbox
  enum Index { kSelect = 0, kSketch = 1, kPress = 2, kIncision = 3, kDffdSplit = 4, kDdmPaint = 5 };

  void set_active(int index);  // deactivates the old tool, activates the new one; out-of-range is ignored
  int active() const { return active_; }
  // Activates the tool whose ToolEntry::shortcut is `key` ("K"); false if none has it.
  bool activate_shortcut(const std::string& key);
  Tool& tool() { return *tools_[active_]; }
  const Tool& tool() const { return *tools_[active_]; }

  void draw_panel(const ui::Rect& rect);      // the docked Tool window
  void handle_mouse(glm::dvec2 mouse_px);     // feeds ImGui's mouse state to the active tool
  void mouse_away() { tool().mouse_away(); }  // the viewport does not get the mouse this frame
  void decorate(gpu::ViewOptions& options) const { tool().decorate(options); }
  // The active tool's live lattice preview (Tool::live_preview), if any.
  std::optional<Tool::LivePreview> live_preview(const ToolContext& ctx) { return tool().live_preview(ctx); }
  std::string hint() const { return tool().hint(); }
  bool owns_mouse() const { return tool().owns_mouse(); }  // the active tool is mid-drag: no navigation

 private:
  ToolContext& ctx_;
  std::vector<std::unique_ptr<Tool>> tools_;
  int active_ = kSelect;
};

}  // namespace trispline::editor
