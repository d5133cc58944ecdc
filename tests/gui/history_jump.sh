#!/usr/bin/env bash
# Undo, redo and History jumps walk the history on a worker (editor/session/background_command.h) while the view stays live:
# tests/logs/ddm_follow.jsonl opened (four tile fills, a DFFD split, a placement), a click on "(initial state)" undoes
# every step in one jump, three quick Ctrl+Shift+Z redo three steps in order (keys typed while a move runs wait for
# it), a click on the last row redoes the rest and the objects and their tile layers come back; the Log names each
# move.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/tests/logs/ddm_follow.jsonl"
gui_wait '(.objects | length) == 6 and .tiles.layers == 4' "the log opens with its six objects and four layers"
n="$(gui_q '.history.labels | length')"
gui_click_item history.row.0
gui_wait '.history.applied == 0 and (.objects | length) == 0' "a click on (initial state) undoes every step"
gui_wait ".log | any(test(\"History: $n steps back\"))" "the Log names the jump"
read -r vx vy <<<"$(gui_q '.viewport | "\(((.[0] + .[2]) / 2) | floor) \(((.[1] + .[3]) / 2) | floor)"')"
gui_move "$vx" "$vy"
gui_frames 1
gui_key ctrl+shift+z ctrl+shift+z ctrl+shift+z
gui_wait '.history.applied == 3' "three quick Ctrl+Shift+Z redo three steps"
gui_frames 3
gui_check '.history.applied == 3 and .objects == ["ground", "cut"]' "three steps and no more: the timeline, two objects"
gui_check '.log[-3:] | map(test("^Redo ")) | all' "the Log names the three redos"
gui_scroll_into_view "history.row.$n" panel.history
gui_click_item "history.row.$n"
gui_wait ".history.applied == $n and (.objects | length) == 6 and .tiles.layers == 4" \
  "a click on the last row redoes the rest: objects and layers back"
gui_wait ".log | any(test(\"History: $((n - 3)) steps forward\"))" "the Log names that jump"
gui_pass
