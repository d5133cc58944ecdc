#include "editor/tools/keyed_weight_section.h"

#include <imgui.h>

#include "editor/session/session.h"
#include "ui/gui_probe.h"

namespace trispline::editor {

void draw_keyed_weight_section(ToolContext& ctx, const KeyedWeightSection& section,
                               const core::ParamSchema<core::KeyedWeightParams>& schema, ui::KeyPairParams& keys,
                               const core::SceneObject* object, const std::string& unavailable, bool keyed) {
  if (!ImGui::CollapsingHeader(section.header, ImGuiTreeNodeFlags_DefaultOpen)) return;
  ui::probe::item(std::string(section.spec.id) + ".header");
  const core::Timeline& timeline = ctx.session.scene().timeline;
  if (keys.frame_to < 0) keys.frame_from = timeline.frame_start, keys.frame_to = timeline.frame_end;
  const ui::KeyPairResult r = ui::draw_key_pair_panel(keys, section.spec, unavailable, keyed);
  if (!(r.animate || r.clear) || !object) return;
  core::KeyedWeightParams p;
  p.object = object->name;
  p.clear = r.clear;
  if (r.animate) p.keys = ui::key_pair_keys(keys), p.interpolation = keys.interpolation;
  ctx.execute_deferred(section.working + object->name, schema.to_json(p));
}

}  // namespace trispline::editor
