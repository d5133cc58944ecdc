#include "editor/tools/dffd_tool.h"

#include <imgui.h>

#include "editor/navigation.h"
#include "editor/session.h"
#include "editor/tools/select_tool.h"
#include "ui/theme.h"

namespace trispline::editor {

ui::ToolEntry DffdTool::entry() const {
  return {"Split (DFFD)", "", "Split the selected object around obstacles: it wraps around them and re-forms behind"};
}

std::string DffdTool::hint() const {
  return "Click: select   Tool panel: tick obstacles, then Split";
}

std::vector<ui::DffdObstacleInfo> DffdTool::candidates(const ToolContext& ctx, const std::string& object) const {
  std::vector<ui::DffdObstacleInfo> out;
  for (const core::SceneObject& o : ctx.session.scene().objects()) {
    if (o.name == object || !o.visible || ctx.hidden.count(o.name) || !o.world_mesh || o.world_mesh->empty())
      continue;
    auto& cached = extents_[o.name];
    if (cached.first.lock() != o.world_mesh) {
      const core::Aabb box = bounds_of(*o.world_mesh);
      cached = {o.world_mesh, box.hi - box.lo};
    }
    out.push_back({o.name, cached.second});
  }
  return out;
}

void DffdTool::split(ToolContext& ctx, const nlohmann::json& line) {
  EditorSession& session = ctx.session;  // outlives the deferred work; ctx may not
  ctx.defer("Splitting " + line.value("object", std::string()), [&session, line]() { session.execute(line); });
}

void DffdTool::draw_panel(ToolContext& ctx) {
  const std::string object = ctx.session.scene().find(ctx.selected) ? ctx.selected : std::string();
  const ui::DffdPanelResult r = ui::draw_dffd_panel(params_, object, candidates(ctx, object));
  if (r.line) split(ctx, *r.line);
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextWrapped(
      "The lattice spans the obstacles' bounding box grown to hold the part of the object that must split; "
      "each obstacle opens a discontinuity at its centre along u. One split is one undoable step.");
}

void DffdTool::decorate(gpu::ViewOptions& options) const { options.show_discontinuities = true; }

}  // namespace trispline::editor
