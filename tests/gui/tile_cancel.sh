#!/usr/bin/env bash
# Tile Paint's Fill built on a worker thread: a small tile size typed on the default scene's teapot makes a long
# fill; its progress bar shows (probe value command.progress) while the view keeps drawing, Cancel stops it and
# nothing is logged or added to the history ("Fill cancelled" in the Log); Fill again runs to the end and logs one
# ddm.fill line.
# 6 frames per second (not 3): the Cancel click must land within the fill's couple of seconds.
GUI_FPS=6
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
# One core for the editor's threads: the fill below then takes a few seconds on any machine, time to click Cancel.
taskset -a -p -c 0 "$GUI_PID" >/dev/null || gui_fail "taskset could not pin the editor to one core"
gui_teapot_tile_paint

# Thorns 0.014 across on the teapot body: about 9 M tile vertices (under the 10 M limit), seconds of building.
gui_click_item ddm.tile_size
gui_wait '.typing' "one click on Tile size enters text editing"
gui_type "0.014"
gui_key Return
gui_wait '(.typing | not) and (.values["ddm.estimate_vertices"] | tonumber) > 8000000' "a long fill"
gui_log "estimate: $(gui_q '.values["ddm.estimate_tiles"]') tiles, $(gui_q '.values["ddm.estimate_vertices"]') tile vertices"
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait '.items["ddm.fill_anyway"] != null' "above the vertex budget Fill asks first"
gui_click_item ddm.fill_anyway
gui_wait '.items["command.cancel"] != null and .values["command.progress"] != null' "the progress bar shows"
gui_log "progress: $(gui_q '.values["command.progress"]') ($(gui_q '.command.what'))"
gui_check '.command != null' "still building when Cancel is clicked"
gui_click_item command.cancel
gui_screenshot progress && gui_log "screenshot of the bar: $GUI_DIR/progress.png"
gui_wait '.command == null' "Cancel ends the build" 60
gui_wait '.log | map(select(test("Fill cancelled"))) | length > 0' "the Log says Fill cancelled"
gui_check "(.history.labels | length) == $n" "Cancel added no history entry"
[ "$(gui_session_count '.cmd == "ddm.fill"')" = 0 ] || gui_fail "a cancelled fill was logged"

# Fill again at a size that finishes soon; it runs to the end as one undoable line.
gui_click_item ddm.tile_size
gui_wait '.typing' "Tile size takes text again"
gui_type "0.05"
gui_key Return
gui_wait '(.typing | not) and (.values["ddm.estimate_vertices"] | tonumber) < 1000000' "a fill under the budget"
tiles="$(gui_q '.values["ddm.estimate_tiles"]')"
gui_click_item ddm.fill
gui_wait "(.history.labels | length) == $((n + 1))" "the fill finishes as one history entry" 90
gui_check '.command == null' "no build left running"
gui_wait_logged '.cmd == "ddm.fill" and .tile_size == 0.05 and .base == "teapot_body"' "ddm.fill logged once done"
[ "$(gui_session_count '.cmd == "ddm.fill"')" = 1 ] || gui_fail "expected one ddm.fill line"
gui_wait '.values["ddm.layer_tiles"] == "'"$tiles"'"' "the fill made the tiles the panel showed"
gui_pass
