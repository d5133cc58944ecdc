#include "editor/tools/dffd_tool.h"

#include <imgui.h>

#include <cstdio>

#include "core/commands/dffd_animate.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/keyed_weight_section.h"
#include "editor/tools/select_tool.h"
#include "ui/gui_probe.h"
#include "ui/theme.h"

namespace trispline::editor {

ui::ToolEntry DffdTool::entry() const {
  return {"Split (DFFD)", "", "Split the selected object around obstacles: it wraps around them and re-forms behind"};
}

std::string DffdTool::hint() const { return "Click: select   Tool panel: tick obstacles, then Split"; }

std::vector<ui::DffdObstacleInfo> DffdTool::candidates(const ToolContext& ctx, const std::string& object) const {
  std::vector<ui::DffdObstacleInfo> out;
  for (const core::SceneObject& o : ctx.session.scene().objects()) {
    if (o.name == object || !o.visible || !o.world_mesh || o.world_mesh->empty()) continue;
    auto& cached = extents_[o.name];
    if (cached.first.lock() != o.world_mesh) {
      const core::Aabb box = core::mesh_bounds(*o.world_mesh);
      cached = {o.world_mesh, box.hi - box.lo};
    }
    out.push_back({o.name, cached.second});
  }
  return out;
}

void DffdTool::split(ToolContext& ctx, const nlohmann::json& line) {
  EditorSession& session = ctx.session;  // outlives the deferred work; ctx may not
  ctx.defer("Splitting " + line.value("object", std::string()), [&session, line]() {
    if (!session.execute(line)) return;
    // The split refined its lattice to clear the obstacles: say by how much (the log line stays as typed).
    const nlohmann::json st = session.history().last_executed().stats();
    if (st.value("refinement_rounds", 0) > 0) {
      const auto& c = st.at("controls_used");
      char clearance[32];
      std::snprintf(clearance, sizeof clearance, "%.3g", st.value("clearance_used", 0.0));
      session.messages().info(line.value("object", std::string()) + ": " +
                              std::to_string(st.value("inside_before_refinement", 0)) +
                              " vertices were inside an obstacle; the lattice was refined to clear them (clearance " +
                              clearance + ", controls " + c.dump() + ")");
    }
    for (const auto& name : st.value("unchecked_obstacles", nlohmann::json::array()))
      session.messages().warning("'" + name.get<std::string>() +
                                 "' does not bound a volume (open or non-manifold): its clearance was not checked");
  });
}

void DffdTool::draw_seam_section(ToolContext& ctx, const std::string& object) {
  static const KeyedWeightSection section{
      "Seam over time",
      {"dffd_anim", "Stitch",
       "0: the openings as the obstacles leave them (capped); 1: stitched behind them at the level w_s (seed section "
       "6.3.2); other values extrapolate",
       "Key the seam at the two frames (one undoable dffd.animate); it plays with the walk",
       "Remove the keys: the seam as the split built it"},
      "Animating the seam of "};
  const core::SceneObject* sel = ctx.session.scene().find(object);
  std::string unavailable;
  if (!sel)
    unavailable = "select an object split by Split (DFFD)";
  else if (!sel->dffd)
    unavailable = "'" + sel->name + "' is not split yet: tick obstacles, then Split";
  else if (!sel->dffd->seam)
    unavailable = "'" + sel->name +
                  "' was split with open openings (no caps): split it "
                  "with openings cap or stitch to key its seam";
  const bool keyed = sel && sel->dffd && !sel->dffd->stitch_keys.empty();
  draw_keyed_weight_section(ctx, section, core::DffdAnimateCommand::schema(), stitch_keys_, sel, unavailable, keyed);
}

void DffdTool::draw_panel(ToolContext& ctx) {
  const std::string object = ctx.session.scene().find(ctx.selected) ? ctx.selected : std::string();
  // A split object shows its seam first (what is left to do with it); otherwise the split's parameters lead.
  const core::SceneObject* sel = ctx.session.scene().find(object);
  const bool split_already = sel && sel->dffd;
  if (split_already) {
    draw_seam_section(ctx, object);
    ImGui::Spacing();
  }
  const ui::DffdPanelResult r = ui::draw_dffd_panel(params_, object, candidates(ctx, object));
  if (r.line) split(ctx, *r.line);
  ImGui::Spacing();
  if (!split_already) draw_seam_section(ctx, object);
  ImGui::Spacing();
  if (const std::optional<nlohmann::json> line = ui::draw_inside_panel(inside_, sel))
    ctx.execute_deferred("Setting the inside of '" + object + "'", *line);
  ImGui::Separator();
  ImGui::TextWrapped(
      "The lattice spans the obstacles' bounding box grown to hold the part of the object that must split; "
      "each obstacle opens a discontinuity at its centre along u. One split is one undoable step.");
}

void DffdTool::decorate(gpu::ViewOptions& options) const { options.show_discontinuities = true; }

}  // namespace trispline::editor
