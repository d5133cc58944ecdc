#!/usr/bin/env bash
# The Sketch tool's panel draws place.sketch's declared parameters: typing a half-width into its field re-runs the
# adopted placement as one undoable step with that width, the Type combo switches the volume to "extrude", and the Fit
# combo (keep by default: the line carries no "fit") switches to "stretch". Each object has its own half-width and
# height (from its size until typed), and an edit that cannot re-run the placement (a step came after it) says why.
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

# The default scene's placement is an offset volume: the Type combo switches it to extrude.
gui_check '.items["place.sketch.volume"] != null' "the panel shows the Type combo"
gui_click_item place.sketch.volume
gui_wait '.popups | length > 0' "the Type combo opens"
gui_click_item place.sketch.volume.extrude
gui_wait_logged '.cmd == "place.sketch" and .volume == "extrude" and .width == 0.25' \
  "choosing extrude in the Type combo logs a place.sketch with volume extrude"
gui_wait '.popups | length == 0' "the Type combo closed"

gui_wait '.items["place.sketch.fit"] != null' "the panel shows the Fit combo"
gui_click_item place.sketch.fit
gui_wait '.popups | length > 0' "the Fit combo opens"
gui_click_item place.sketch.fit.stretch
gui_wait_logged '.cmd == "place.sketch" and .fit == "stretch" and .volume == "extrude"' \
  "choosing stretch in the Fit combo logs a place.sketch with fit stretch"
gui_wait '.popups | length == 0' "the Fit combo closed"
gui_click_item place.sketch.fit
gui_wait '.popups | length > 0' "the Fit combo opens again"
gui_click_item place.sketch.fit.keep
keep_line='.cmd == "place.sketch" and (has("fit") | not) and .volume == "extrude" and .width == 0.25'
for ((i = 0; i < 60; ++i)); do
  [ "$(gui_session_count "$keep_line")" -ge 2 ] && break
  gui_frames 1
done
gui_check "$(gui_session_count "$keep_line") >= 2" "back to keep: a second extrude line that leaves fit to its default"
gui_check "(.history.labels | length) == $n" "each edit replaced the placement: one history entry"

# Per-object sizes: the teapot gets its own half-width and height from its bounds; the bunny keeps the typed 0.25.
gui_click_item scene.object.teapot
gui_wait '.selected == "teapot"' "the teapot is selected"
gui_wait '(.values["sketch.width"] | tonumber) != 0.25 and (.values["sketch.height"] | tonumber) > 0' \
  "the teapot's half-width and height come from its own size"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "the bunny is selected again"
gui_wait '(.values["sketch.width"] | tonumber) == 0.25' "the bunny keeps the half-width typed for it"

# Another step after the placement: an edited Extent cannot re-run it, and the Log says so.
gui_click_item scene.eye.teapot
gui_wait "(.history.labels | length) == $((n + 1))" "hiding the teapot is a step after the placement"
gui_click_item place.sketch.extent
gui_wait '.typing' "one click on Extent enters text editing"
gui_type "0.5"
gui_key Return
gui_wait '.log | map(select(test("apply to the next stroke: the placement of .bunny. is not the latest step"))) | length >= 1' \
  "the Log says why the extent does not re-run the placement"
gui_check "(.history.labels | length) == $((n + 1))" "nothing was re-run"
gui_pass
