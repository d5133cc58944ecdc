// trispline::editor::SelectTool — a left click picks the first visible object under the cursor (ray cast over
// world meshes with core::RayCaster); a click on empty space clears the selection. Selection is view state, not
// a command (as in Blender's viewport, it is not in the command log). Its panel shows the selected object and a
// "Ring lattice" section: lattice.ring's radius, twist (0, or 180 for a Möbius band, seed Figs. 4.5–4.6), phase and
// control points, drawn from the command's schema, and "Bind to ring" (one undoable lattice.ring). Probe items
// "lattice.ring.<field>", "select.ring", "select.ring.bind".
#pragma once

#include <optional>
#include <set>
#include <string>

#include "core/commands/lattice_ring.h"
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
  // The Ring lattice section's values, for ring_.object (reset to its defaults when another object is selected).
  core::LatticeRingParams ring_;
  void draw_ring_section(ToolContext& ctx, const core::SceneObject& o);
};

}  // namespace trispline::editor
