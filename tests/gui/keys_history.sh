#!/usr/bin/env bash
# I twice at one frame keys once (one history entry); Ctrl+Z / Ctrl+Shift+Z undo and redo it; shortcuts pressed
# faster than the frames come are each applied, in order.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"
gui_move "$(gui_q '((.viewport[0] + .viewport[2]) / 2) | floor')" "$(gui_q '((.viewport[1] + .viewport[3]) / 2) | floor')"
gui_frames 1
n="$(gui_q '.history.labels | length')"
gui_key i
gui_wait "(.history.labels | length) == $((n + 1))" "I keys the offset"
gui_key i
gui_frames 3
gui_check "(.history.labels | length) == $((n + 1))" "I again at the same frame adds no entry"
gui_key ctrl+z
gui_wait ".history.applied == $n" "Ctrl+Z undoes the key"
gui_key ctrl+shift+z
gui_wait ".history.applied == $((n + 1))" "Ctrl+Shift+Z redoes it"
# Presses typed faster than frames are drawn (three within one 0.33 s frame) all act, in order.
gui_key ctrl+z ctrl+z ctrl+z
gui_wait ".history.applied == $((n - 2))" "three quick Ctrl+Z undo three steps"
gui_key ctrl+shift+z ctrl+shift+z ctrl+shift+z
gui_wait ".history.applied == $((n + 1))" "three quick Ctrl+Shift+Z redo them"
gui_pass
