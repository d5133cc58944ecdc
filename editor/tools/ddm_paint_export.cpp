// The Tile Paint panel's map export row: a layer's position or normal map (seed Figs. 5.3, 5.5) written as a PNG
// through the Save dialog, one ddm.export line in the History and the session log.
#include <imgui.h>

#include "core/commands/ddm_export.h"
#include "editor/session/session.h"
#include "editor/tools/ddm_paint_tool.h"
#include "ui/gui_probe.h"
#include "ui/theme.h"

namespace trispline::editor {

namespace {
struct MapKind {
  const char* what;   // ddm.export's "what"
  const char* label;  // button text
  const char* tooltip;
};
constexpr MapKind kMapKinds[] = {
    {"positions", "Position map...",
     "Save the layer's position map P(u, v) as a PNG (seed Fig. 5.3): x, y, z over the surface's bounding box as red, "
     "green, blue; texels the diffusion filled are faded. One ddm.export"},
    {"normals", "Normal map...",
     "Save the layer's normal map N(u, v) as a PNG (seed Fig. 5.5): unit normals as (n + 1) / 2 in red, green, blue; "
     "texels the diffusion filled are faded. One ddm.export"},
};
}  // namespace

void DdmPaintTool::draw_map_export(ToolContext& ctx) {
  const core::SceneObject* o = target(ctx);
  ImGui::BeginDisabled(!o || new_layer(ctx) || !ctx.save_file);
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("Export");
  for (const MapKind& kind : kMapKinds) {
    ImGui::SameLine();
    if (ImGui::Button(kind.label)) {
      const std::string object = o->name, layer = params_.paint.layer, what = kind.what;
      EditorSession& session = ctx.session;
      ctx.save_file(
          "Save the " + std::string(what == "positions" ? "position" : "normal") + " map of " + object + "/" + layer,
          ".png", object + "_" + layer + "_" + what + ".png",
          [&session, object, layer, what](const std::filesystem::path& file) {
            export_map(session, object, layer, what, file);
          });
    }
    ui::probe::item(std::string("ddm.export.") + kind.what);
    ui::tooltip(kind.tooltip);
  }
  ImGui::EndDisabled();
}

bool DdmPaintTool::export_map(EditorSession& session, const std::string& object, const std::string& layer,
                              const std::string& what, const std::filesystem::path& file) {
  core::DdmExportParams p;
  p.object = object;
  p.layer = layer;
  p.what = what;
  // The user chose the file in a dialog: its folder is the output folder, and the line names the file in it.
  p.path = file.filename().string();
  if (!session.execute(core::DdmExportCommand::schema().to_json(p), {}, file.parent_path())) return false;
  session.messages().info("saved the " + what + " map of " + object + "/" + layer + " to " + file.string());
  return true;
}

}  // namespace trispline::editor
