#!/usr/bin/env bash
# Press tool: a Ctrl+drag pulls, and History says "Pull". A drag that begins on the bunny and ends with the button
# released over the Log panel still ends the stroke: one more history entry (the release belongs to the drag, as in
# any editor, not to the panel under the cursor).
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"
x="$(gui_q '.object_centroid_px.bunny[0] | floor')"; y="$(gui_q '.object_centroid_px.bunny[1] | floor')"
gui_move "$x" "$y"
gui_frames 1
gui_key e
gui_wait '.tool == "Press"' "E picks the Press tool"
n="$(gui_q '.history.labels | length')"
gui_frames 3
gui_drag "$x" "$y" $((x - 12)) $((y + 6)) ctrl  # down-left: away from the timing overlay above
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the drag" 60
gui_check '.history.labels | last | startswith("Pull")' "the Ctrl+drag is labelled Pull"

# Down on the bunny, moves in the view, then the button comes up over the Log panel.
n="$(gui_q '.history.labels | length')"
gui_move "$x" "$y"
gui_frames 2
gui_wait '.overlays.spheres > 0' "the brush sphere shows over the bunny before the button goes down" 30
xdotool mousedown 1
gui_frames 3
gui_move $((x - 8)) $((y + 4))
gui_frames 2
read -r lx ly <<<"$(gui_item_center panel.log)"
gui_move "$lx" "$ly"
gui_frames 2
xdotool mouseup 1
gui_wait "(.history.labels | length) == $((n + 1))" "a drag released over the Log panel still ends with one entry" 60
gui_check '.history.labels | last | startswith("Press")' "the plain drag is labelled Press"
gui_pass
