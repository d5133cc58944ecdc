#!/usr/bin/env bash
# Tile Paint's sizes follow the chosen object: the bunny gets its own tile size and height (from its size in object
# space, where tiles are laid), not the teapot's; a height typed for the bunny stays the bunny's when the teapot is
# chosen and back; a height beyond the bunny's size is limited, and the field and the Log say so.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_teapot_tile_paint
h_pot="$(gui_q '.values["ddm.height"] | tonumber')"
s_pot="$(gui_q '.values["ddm.tile_size"] | tonumber')"
gui_log "teapot: tile size $s_pot, height $h_pot"

gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"
gui_wait "(.values[\"ddm.height\"] | tonumber) != $h_pot and (.values[\"ddm.tile_size\"] | tonumber) != $s_pot" \
  "the bunny's tile size and height are its own, not the teapot's"
h_bunny="$(gui_q '.values["ddm.height"] | tonumber')"
gui_log "bunny: tile size $(gui_q '.values["ddm.tile_size"]'), height $h_bunny"

gui_click_item ddm.height
gui_wait '.typing' "one click on Height enters text editing"
gui_type "0.0123"
gui_key Return
gui_wait '(.typing | not) and (.values["ddm.height"] | tonumber) == 0.0123' "height 0.0123 typed for the bunny"

gui_click_item scene.object.teapot
gui_wait '.selected == "teapot"' "teapot selected again"
gui_wait "(.values[\"ddm.height\"] | tonumber) == $h_pot" "the teapot gets its own height back"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected again"
gui_wait '(.values["ddm.height"] | tonumber) == 0.0123' "the bunny keeps the height typed for it"

# A height beyond what the bunny takes is limited to ddm.fill's declared maximum (1 × its bounding-box diagonal): the
# field turns amber with the reason, and the Log says it once.
gui_click_item ddm.height
gui_wait '.typing' "Height again"
gui_type "50"
gui_key Return
gui_wait '.log | map(select(test("Tile height 50: Limited to [0-9.e+-]+: the height is at most 1 x"))) | length == 1' \
  "the Log says the height was limited"
gui_wait '.values["ddm.height.limited"] | test("Limited to")' "the Height field is amber, with the reason"
gui_wait '(.values["ddm.height"] | tonumber) < 50' "the height kept is the limit"
gui_shot limited
gui_pass
