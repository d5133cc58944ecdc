#include "ui/ddm_anim_panel.h"

#include <imgui.h>

#include <algorithm>

#include "core/commands/ddm_animate.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"

namespace trispline::ui {

bool ddm_anim_keyed(const DdmAnimParams& p) {
  return !p.morph_tile.empty() || p.turn_from != 0.0 || p.turn_to != 0.0 || p.scale_from != 1.0 || p.scale_to != 1.0 ||
         p.w_from != 1.0 || p.w_to != 1.0;
}

std::string ddm_animate_blocked(const std::string& object, const std::string& layer, const DdmAnimParams& p) {
  if (object.empty()) return "select an object with a tile layer";
  if (layer.empty()) return "the object has no tile layer: fill or paint one first";
  if (ddm_anim_keyed(p) && p.frame_from >= p.frame_to) return "the keys need frame from < frame to";
  if (!(p.scale_from > 0.0 && p.scale_to > 0.0)) return "the scale must be > 0";
  if (!(p.w_from > 0.0 && p.w_to > 0.0)) return "w (the height factor) must be > 0";
  if (!ddm_anim_keyed(p) && p.speed_u == 0.0 && p.speed_v == 0.0)
    return "nothing to animate: choose a morph tile, a turn, a scale, a w or an offset speed";
  return "";
}

namespace {
// Two keys over the panel's frames, or none when both values are `rest` (the list then removes that animation).
std::vector<glm::dvec2> key_pair(const DdmAnimParams& p, double from, double to, double rest) {
  if (from == rest && to == rest) return {};
  return {{p.frame_from, from}, {p.frame_to, to}};
}
}  // namespace

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
    a.rotate_keys = key_pair(p, p.turn_from, p.turn_to, 0.0);
    a.scale_keys = key_pair(p, p.scale_from, p.scale_to, 1.0);
    a.w_keys = key_pair(p, p.w_from, p.w_to, 1.0);
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
  const bool morph_open = ImGui::BeginCombo("##morph", shown);
  probe::item("ddm_anim.morph");
  probe::value("ddm_anim.morph", p.morph_tile);
  if (morph_open) {
    for (const char* m : morphs) {
      const std::string value = std::string(m) == "(none)" ? "" : m;
      if (ImGui::Selectable(m, value == p.morph_tile)) p.morph_tile = value;
      probe::item("ddm_anim.morph." + (value.empty() ? std::string("none") : value));
    }
    ImGui::EndCombo();
  }
  tooltip(
      "Metamorphosis partner (seed Eq. 5.3): V = V1(1 - alpha) + V2 alpha, normals renormalised. It needs the "
      "tile's topology: thorn and flower are partners.");
  row_label("Frames");
  int frames[2] = {p.frame_from, p.frame_to};
  if (drag_int_n("##frames", frames, 2, 0.5f, 0, 100000)) p.frame_from = frames[0], p.frame_to = frames[1];
  probe::item("ddm_anim.frames");
  tooltip("Timeline frames of the two keys of every keyed value below (alpha, turn, scale, w)");
  ImGui::BeginDisabled(p.morph_tile.empty());
  row_label("Alpha");
  double alphas[2] = {p.alpha_from, p.alpha_to};
  if (drag_scalar_n("##alpha", ImGuiDataType_Double, alphas, 2, 0.01f, nullptr, nullptr, "%.2f"))
    p.alpha_from = alphas[0], p.alpha_to = alphas[1];
  tooltip("Alpha at the two keys; values outside [0, 1] extrapolate the shapes");
  ImGui::EndDisabled();
  // Texture-space transform and w of the tiles (seed section 5.4.2), relative to the layer's own.
  const auto pair_row = [](const char* label, const char* id, double* from, double* to, float speed, const char* format,
                           const char* probe_name, const char* help) {
    row_label(label);
    double v[2] = {*from, *to};
    if (drag_scalar_n(id, ImGuiDataType_Double, v, 2, speed, nullptr, nullptr, format)) *from = v[0], *to = v[1];
    probe::item(probe_name);
    tooltip(help);
  };
  pair_row("Turn", "##turn", &p.turn_from, &p.turn_to, 1.0f, "%.1f deg", "ddm_anim.turn",
           "Rotation of every tile about its cell's centre in texture space at the two keys, degrees added to the "
           "layer's own (0 and 360: one full turn). Both 0: the tiles do not turn.");
  pair_row("Scale", "##scale", &p.scale_from, &p.scale_to, 0.01f, "%.2f", "ddm_anim.scale",
           "Size of every tile in its cell at the two keys, times the layer's own scale (> 0). Both 1: no scale keys.");
  pair_row("Height x", "##w", &p.w_from, &p.w_to, 0.01f, "%.2f", "ddm_anim.w",
           "w: the tiles' height along the surface normal at the two keys, times the layer's height (> 0). Both 1: "
           "no w keys.");
  row_label("Offset speed");
  double speed[2] = {p.speed_u, p.speed_v};
  if (drag_scalar_n("##speed", ImGuiDataType_Double, speed, 2, 0.001f, nullptr, nullptr, "%.3f /s"))
    p.speed_u = speed[0], p.speed_v = speed[1];
  probe::item("ddm_anim.speed");
  tooltip(
      "Texture-space offset of every tile, chart units per second (seed section 5.4.2). On the teapot body, "
      "u = 1 is one turn round the pot.");
  row_label("Easing");
  if (ImGui::BeginCombo("##interp", p.interpolation.c_str())) {
    for (const std::string& name : core::DdmAnimateCommand::schema().find("interpolation")->choices)
      if (ImGui::Selectable(name.c_str(), name == p.interpolation)) p.interpolation = name;
    ImGui::EndCombo();
  }
  tooltip("How every keyed value moves between its two keys (Blender's keyframe interpolation)");
  const std::string blocked = ddm_animate_blocked(object, layer, p);
  probe::value("ddm_anim.blocked", blocked);
  ImGui::BeginDisabled(!blocked.empty());
  if (ImGui::Button("Animate")) r.line = ddm_animate_line(object, layer, p);
  ImGui::EndDisabled();
  probe::item("ddm_anim.animate");
  tooltip(blocked.empty() ? "Set this layer's animation (one undoable ddm.animate); press play to watch it"
                          : blocked.c_str());
  ImGui::SameLine();
  ImGui::BeginDisabled(object.empty() || layer.empty());
  if (ImGui::Button("Clear")) r.line = ddm_animate_line(object, layer, p, true);
  ImGui::EndDisabled();
  probe::item("ddm_anim.clear");
  tooltip("Remove the layer's animation");
  ImGui::PopID();
  return r;
}

}  // namespace trispline::ui
