#!/usr/bin/env bash
# Press tool: a Ctrl+drag pulls, and History says "Pull".
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
gui_pass
