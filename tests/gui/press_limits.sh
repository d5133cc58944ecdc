#!/usr/bin/env bash
# The Press tool's Radius and Strength take one click and typed text (no jump to the click position), and a typed
# value beyond what the object takes is limited where the user looks: the field turns amber, its tooltip and the Log
# say why; a value in range clears it.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"
gui_move 640 300
gui_frames 1
gui_key e
gui_wait '.tool == "Press"' "E picks the Press tool"
gui_wait '.items["press.radius"] != null' "the panel shows Radius"
r0="$(gui_q '.values["press.radius"] | tonumber')"

gui_click_item press.radius
gui_wait '.typing' "one click on Radius enters text editing"
gui_check "(.values[\"press.radius\"] | tonumber) == $r0" "the click did not move the radius"
gui_type "0.07"
gui_key Return
gui_wait '(.typing | not) and (.values["press.radius"] | tonumber) == 0.07' "radius 0.07 typed"
gui_check '.values["press.radius.limited"] == ""' "a radius in range is not limited"
gui_check '.log | map(select(test("Press radius"))) | length == 0' "typing 0.07 (through 0 and 0.0) warned of nothing"

gui_click_item press.strength
gui_wait '.typing' "one click on Strength enters text editing"
gui_type "1.5"
gui_key Return
gui_wait '(.typing | not) and (.values["press.strength.limited"] | startswith("Limited to"))' \
  "a strength of 1.5 is limited, and the field says so"
gui_check '(.values["press.strength"] | tonumber) < 1.5' "the strength used is below the typed 1.5"
gui_wait '.log | map(select(test("Press strength 1.5: Limited to"))) | length == 1' "the Log says the strength was limited"
read -r sx sy <<<"$(gui_item_center press.strength)"
gui_move "$sx" "$sy"
gui_wait '.tooltip == true' "hovering Strength shows its tooltip (with the reason)"
gui_shot limited

gui_click_item press.radius
gui_wait '.typing' "Radius again"
gui_type "100"
gui_key Return
gui_wait '(.values["press.radius.limited"] | startswith("Limited to"))' "a radius of 100 is limited to half the diagonal"

gui_click_item press.strength
gui_wait '.typing' "Strength again"
gui_type "0.02"
gui_key Return
gui_wait '(.typing | not) and .values["press.strength.limited"] == "" and (.values["press.strength"] | tonumber) == 0.02' \
  "a strength in range clears the warning"

# Radius and strength are the object's: the teapot gets its own (from its size), the bunny gets back what was typed.
r_bunny="$(gui_q '.values["press.radius"]')"
gui_click_item scene.object.teapot
gui_wait '.selected == "teapot"' "the teapot is selected"
gui_wait "(.values[\"press.radius\"] | tonumber) != ($r_bunny | tonumber) and (.values[\"press.strength\"] | tonumber) != 0.02" \
  "the teapot's radius and strength come from its own size"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "the bunny is selected again"
gui_wait "(.values[\"press.radius\"] | tonumber) == ($r_bunny | tonumber) and (.values[\"press.strength\"] | tonumber) == 0.02" \
  "the bunny keeps the radius and strength typed for it"
gui_pass
