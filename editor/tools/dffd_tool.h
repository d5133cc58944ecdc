// trispline::editor::DffdTool — "Split (DFFD)": the selected object splits around obstacles, wraps around them and
// re-forms behind (global discontinuous FFD, seed §6.3.1–6.3.2, Fig. 6.4, 6.10, 6.11). The Tool panel
// (ui/dffd_panel.h) ticks obstacles among the other visible objects and sets the lattice and opening parameters; its
// "Split" button executes ONE `dffd.split` command through the session (errors go to the Log panel, the scene stays
// as it was). In the viewport a click selects the object under the cursor, as the Select tool does; while the tool
// is active the view shows the discontinuity planes (gpu::ViewOptions::show_discontinuities). Below, the Inside
// section (ui/inside_panel.h) sets the colour and texture of the selected object's caps: one `object.inside`.
#pragma once

#include <map>
#include <memory>

#include "editor/tools/select_tool.h"
#include "ui/dffd_panel.h"
#include "ui/inside_panel.h"
#include "ui/key_pair_panel.h"

namespace trispline::editor {

// Clicks select as in SelectTool (its handle_input).
class DffdTool : public SelectTool {
 public:
  ui::ToolEntry entry() const override;
  void draw_panel(ToolContext& ctx) override;
  void decorate(gpu::ViewOptions& options) const override;
  std::string hint() const override;

  core::DffdSplitParams& params() { return params_; }
  // The visible objects other than `object` with their world bounding-box extents (obstacle candidates).
  std::vector<ui::DffdObstacleInfo> candidates(const ToolContext& ctx, const std::string& object) const;
  // What the Split button does: executes `line` (a dffd.split) through the session, after one "Working…" frame.
  void split(ToolContext& ctx, const nlohmann::json& line);
  // The "Seam over time" section for `object` (dffd.animate keys at two frames).
  void draw_seam_section(ToolContext& ctx, const std::string& object);

 private:
  core::DffdSplitParams params_;
  ui::KeyPairParams stitch_keys_{1, -1, 0.0, 1.0, "smooth"};  // frame_to < 0: the timeline's end when first shown
  ui::InsidePanelState inside_;
  // Bounding-box extent per object, cached on its world_mesh (an O(#V) pass each panel frame otherwise).
  mutable std::map<std::string, std::pair<std::weak_ptr<const core::TriMesh>, glm::dvec3>> extents_;
};

}  // namespace trispline::editor
