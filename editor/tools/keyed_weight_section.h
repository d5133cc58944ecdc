// trispline::editor keyed-weight section — the "… over time" part of a tool panel whose command keys a blend weight
// s of the selected object at two timeline frames: the Split tool's seam (dffd.animate "stitch_keys", seed §6.3.2)
// and the Incision tool's opening (incision.animate "opening_keys", seed §6.4). ui::draw_key_pair_panel draws the
// keys; Animate or Clear issues the command's line as one undoable step (deferred one frame behind "Working…").
#pragma once

#include <string>

#include "core/commands/anim_keys.h"
#include "editor/tools/tool.h"
#include "ui/key_pair_panel.h"

namespace trispline::editor {

// The section's words; spec.id also names its header for GUI tests ("<id>.header").
struct KeyedWeightSection {
  const char* header;  // "Seam over time"
  ui::KeyPairSpec spec;
  const char* working;  // the "Working…" text before the object's name, e.g. "Animating the seam of "
};

// Draws the collapsible section into the Tool panel. `keys`' frame_to < 0 is replaced by the timeline's range when
// first shown. `object` is the selected object (null: none); a non-empty `unavailable` disables Animate with that
// reason; `keyed` enables Clear. `schema` writes the command's line (dffd.animate's or incision.animate's).
void draw_keyed_weight_section(ToolContext& ctx, const KeyedWeightSection& section,
                               const core::ParamSchema<core::KeyedWeightParams>& schema, ui::KeyPairParams& keys,
                               const core::SceneObject* object, const std::string& unavailable, bool keyed);

}  // namespace trispline::editor
