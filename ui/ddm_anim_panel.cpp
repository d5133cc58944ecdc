#include "ui/ddm_anim_panel.h"

#include <imgui.h>

#include <algorithm>

#include "core/commands/ddm_animate.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"

namespace trispline::ui {

std::string ddm_animate_blocked(const std::string& object, const std::string& layer, const DdmAnimParams& p) {
  if (object.empty()) return "select an object with a tile layer";
  if (layer.empty()) return "the object has no tile layer: fill or paint one first";
  if (!p.morph_tile.empty() && p.frame_from >= p.frame_to) return "the α keys need frame from < frame to";
  if (p.morph_tile.empty() && p.speed_u == 0.0 && p.speed_v == 0.0)
    return "nothing to animate: choose a morph tile or an offset speed";
  return "";
}

nlohmann::json ddm_animate_line(const std::string& object, const std::string& layer, const DdmAnimParams& p,
                                bool clear) {
  core::DdmAnimateParams a;
  a.object = object;
  a.layer = layer;
  a.clear = clear;
  if (!clear) {
    a.morph = std::vector<std::string>{p.morph_tile};
    if (!p.morph_tile.empty())
      a.alpha_keys = std::vector<glm::dvec2>{{p.frame_from, p.alpha_from}, {p.frame_to, p.alpha_to}};
    else
      a.alpha_keys = std::vector<glm::dvec2>{}, a.alpha = 0.0;
    a.offset_velocity = glm::dvec2(p.speed_u, p.speed_v);
    a.interpolation = p.interpolation;
  }
  return core::DdmAnimateCommand::schema().to_json(a);
}

DdmAnimPanelResult draw_ddm_anim_panel(DdmAnimParams& p, std::string& layer, const std::string& object,
                                       const std::vector<DdmLayerInfo>& layers) {
  DdmAnimPanelResult r;
  ImGui::PushID("ddm_anim");
  const auto found = std::find_if(layers.begin(), layers.end(), [&](const DdmLayerInfo& l) { return l.name == layer; });
  if (found == layers.end()) layer = layers.empty() ? "" : layers.front().name;
  row_label("Layer");
  if (ImGui::BeginCombo("##layer", layer.empty() ? "(none)" : layer.c_str())) {
    for (const DdmLayerInfo& l : layers) {
      if (ImGui::Selectable(l.name.c_str(), l.name == layer)) layer = l.name;
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: %zu tiles, %zu vertices%s", l.tile.c_str(), l.tiles, l.vertices,
                          l.animated ? ", animated" : "");
    }
    ImGui::EndCombo();
  }
  tooltip("The tile layer of the selected object to animate");
  row_label("Morph to");
  const char* morphs[] = {"flower", "thorn", "(none)"};
  const char* shown = p.morph_tile.empty() ? "(none)" : p.morph_tile.c_str();
  if (ImGui::BeginCombo("##morph", shown)) {
    for (const char* m : morphs) {
      const std::string value = std::string(m) == "(none)" ? "" : m;
      if (ImGui::Selectable(m, value == p.morph_tile)) p.morph_tile = value;
    }
    ImGui::EndCombo();
  }
  tooltip(
      "Metamorphosis partner (seed Eq. 5.3): V = V1(1 - alpha) + V2 alpha, normals renormalised. It needs the "
      "tile's topology: thorn and flower are partners.");
  ImGui::BeginDisabled(p.morph_tile.empty());
  row_label("Frames");
  int frames[2] = {p.frame_from, p.frame_to};
  if (drag_int_n("##frames", frames, 2, 0.5f, 0, 100000)) p.frame_from = frames[0], p.frame_to = frames[1];
  tooltip("Timeline frames of the two alpha keys");
  row_label("Alpha");
  double alphas[2] = {p.alpha_from, p.alpha_to};
  if (drag_scalar_n("##alpha", ImGuiDataType_Double, alphas, 2, 0.01f, nullptr, nullptr, "%.2f"))
    p.alpha_from = alphas[0], p.alpha_to = alphas[1];
  tooltip("Alpha at the two keys; values outside [0, 1] extrapolate the shapes");
  ImGui::EndDisabled();
  row_label("Offset speed");
  double speed[2] = {p.speed_u, p.speed_v};
  if (drag_scalar_n("##speed", ImGuiDataType_Double, speed, 2, 0.001f, nullptr, nullptr, "%.3f /s"))
    p.speed_u = speed[0], p.speed_v = speed[1];
  tooltip(
      "Texture-space offset of every tile, chart units per second (seed section 5.4.2). On the teapot body, "
      "u = 1 is one turn round the pot.");
  row_label("Easing");
  if (ImGui::BeginCombo("##interp", p.interpolation.c_str())) {
    for (const std::string& name : core::DdmAnimateCommand::schema().find("interpolation")->choices)
      if (ImGui::Selectable(name.c_str(), name == p.interpolation)) p.interpolation = name;
    ImGui::EndCombo();
  }
  tooltip("How alpha moves between its keys (Blender's keyframe interpolation)");
  const std::string blocked = ddm_animate_blocked(object, layer, p);
  ImGui::BeginDisabled(!blocked.empty());
  if (ImGui::Button("Animate")) r.line = ddm_animate_line(object, layer, p);
  ImGui::EndDisabled();
  tooltip(blocked.empty() ? "Set this layer's animation (one undoable ddm.animate); press play to watch it"
                          : blocked.c_str());
  ImGui::SameLine();
  ImGui::BeginDisabled(object.empty() || layer.empty());
  if (ImGui::Button("Clear")) r.line = ddm_animate_line(object, layer, p, true);
  ImGui::EndDisabled();
  tooltip("Remove the layer's animation");
  ImGui::PopID();
  return r;
}

}  // namespace trispline::ui
