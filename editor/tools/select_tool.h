// trispline::editor::SelectTool — a left click picks the first visible object under the cursor (ray cast over
// world meshes with core::RayCaster); a click on empty space clears the selection. Selection is view state, not
// a command (as in Blender's viewport, it is not in the command log).
#pragma once

#include <optional>
#include <set>
#include <string>

#include "core/scene/scene.h"
#include "editor/tools/tool.h"

namespace trispline::editor {

// Name of the first viewport-visible object or volume (its iso-surface, core::iso_ray_hit) hit by the ray through
// viewport pixel `px`, if any.
std::optional<std::string> pick_object(const core::Scene& scene, const core::Camera& camera, glm::dvec2 px);

class SelectTool : public Tool {
 public:
  ui::ToolEntry entry() const override;
  void handle_input(const ToolInput& in, ToolContext& ctx) override;
  void draw_panel(ToolContext& ctx) override;
  std::string hint() const override { return "Click: select   Middle drag: orbit   Wheel: zoom"; }

 private:
  glm::dvec2 press_px_{0};
  bool pressed_ = false;
};

}  // namespace trispline::editor
