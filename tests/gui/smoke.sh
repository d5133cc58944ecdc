#!/usr/bin/env bash
# The harness itself: the editor starts at 3 fps with its probe, the default scene opens, a named widget is found
# and clicked through real X input, and a command reaches the session log.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.objects | length) >= 2 and (.history.labels | length) >= 4' "the default scene is open"
gui_check '.popups == [] and (.viewport | length) == 4 and (.items["scene.load"] != null)' "probe fields"
gui_click_item scene.object.teapot
gui_wait '.selected == "teapot"' "a click on the Scene panel's row selects the teapot"
[ "$(gui_session_count '.cmd == "place.sketch"')" -ge 1 ] || gui_fail "the session log has the replayed scene"
gui_pass
