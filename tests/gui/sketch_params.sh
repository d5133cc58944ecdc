#!/usr/bin/env bash
# The Sketch tool's panel draws place.sketch's declared parameters: typing a half-width into its field re-runs the
# adopted placement as one undoable step with that width, and the Type combo switches the volume to "offset".
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
n="$(gui_q '.history.labels | length')"
gui_key w
gui_wait '.tool == "Sketch placement"' "W picks the Sketch tool"
gui_wait '.items["place.sketch.width"] != null' "the panel shows the declared Half-width field"

gui_click_item place.sketch.width
gui_wait '.typing' "one click on Half-width enters text editing"
gui_type "0.25"
gui_key Return
gui_wait '.typing | not' "Enter leaves the field"
gui_wait_logged '.cmd == "place.sketch" and .width == 0.25 and .object == "bunny"' "a place.sketch with width 0.25"

gui_click_item place.sketch.volume
gui_wait '.popups | length > 0' "the Type combo opens"
gui_click_item place.sketch.volume.offset
gui_wait_logged '.cmd == "place.sketch" and .volume == "offset" and .width == 0.25' \
  "choosing offset in the Type combo logs a place.sketch with volume offset"
gui_check "(.history.labels | length) == $n" "each edit replaced the placement: one history entry"
gui_pass
