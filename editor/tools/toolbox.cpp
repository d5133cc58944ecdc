#include "editor/tools/toolbox.h"

#include <imgui.h>

#include "editor/tools/ddm_paint_tool.h"
#include "editor/tools/dffd_tool.h"
#include "editor/tools/incision_tool.h"
#include "editor/tools/press_tool.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/sketch_tool.h"
#include "ui/tool_panel.h"

namespace trispline::editor {

Toolbox::Toolbox(ToolContext& ctx) : ctx_(ctx) {
  tools_.push_back(std::make_unique<SelectTool>());
  tools_.push_back(std::make_unique<SketchTool>());
  tools_.push_back(std::make_unique<PressTool>());
  tools_.push_back(std::make_unique<IncisionTool>());
  tools_.push_back(std::make_unique<DffdTool>());
  tools_.push_back(std::make_unique<DdmPaintTool>());
}

bool Toolbox::activate_shortcut(const std::string& key) {
  for (std::size_t i = 0; i < tools_.size(); ++i)
    if (!key.empty() && tools_[i]->entry().shortcut == key) {
      set_active(int(i));
      return true;
    }
  return false;
}

void Toolbox::set_active(int index) {
  if (index == active_ || index < 0 || index >= int(tools_.size())) return;
  tools_[active_]->deactivate(ctx_);
  active_ = index;
  tools_[active_]->activate(ctx_);
}

void Toolbox::draw_panel(const ui::Rect& rect) {
  std::vector<ui::ToolEntry> entries;
  for (const auto& t : tools_) entries.push_back(t->entry());
  int chosen = active_;
  if (ui::begin_tool_panel(rect, entries, &chosen)) tool().draw_panel(ctx_);
  ui::end_tool_panel();
  set_active(chosen);
}

void Toolbox::handle_mouse(glm::dvec2 mouse_px) {
  const ImGuiIO& io = ImGui::GetIO();
  ToolInput in;
  in.mouse_px = mouse_px;
  in.left_pressed = io.MouseClicked[0];
  in.left_down = io.MouseDown[0];
  in.left_released = io.MouseReleased[0];
  in.shift = io.KeyShift;
  in.ctrl = io.KeyCtrl;
  tool().handle_input(in, ctx_);
}

}  // namespace trispline::editor
