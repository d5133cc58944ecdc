#!/usr/bin/env bash
# Keying seams in the real editor: tests/logs/anim_keys.jsonl (a sphere cut by an incision, a sphere split around a
# cylinder). The Split (DFFD) tool's "Seam over time" and the Incision tool's "Opening over time" panels: a typed
# frame, Animate → one dffd.animate / incision.animate in History and the session log with those keys, the object
# animated (frames 1 and 12 differ on screen), Ctrl+Z takes it back, Clear removes the keys.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/tests/logs/anim_keys.jsonl"
gui_wait '(.objects | length) == 3' "the log opens with its three objects"
gui_check '(.animated | length) == 0' "nothing is animated yet"

# --- the DFFD seam -------------------------------------------------------------------------------------------------
gui_click_item scene.object.ball
gui_wait '.selected == "ball"' "the split sphere is selected"
gui_click_item "tool.Split (DFFD)"
gui_wait '.tool == "Split (DFFD)"' "the Split (DFFD) tool is active"
n="$(gui_q '.history.labels | length')"
gui_scroll_into_view dffd_anim.animate
gui_click_item dffd_anim.frame_to
gui_wait '.typing' "one click on To frame enters text editing"
gui_type "12"
gui_key Return
gui_wait '.typing | not' "Enter applies the frame"
gui_click_item dffd_anim.animate
gui_wait "(.history.labels | length) == $((n + 1))" "Animate adds one history entry"
gui_wait_logged '.cmd == "dffd.animate" and .object == "ball" and .stitch_keys == [[1.0,0.0],[12.0,1.0]]' \
  "dffd.animate logged with the typed frame"
gui_wait '.animated | index("ball") != null' "the split sphere is animated"
gui_frames 2
gui_screenshot seam1 || gui_fail "no screenshot at frame 1"
gui_click_item timeline.frame
gui_wait '.typing' "one click on the frame field enters text editing"
gui_type "12"
gui_key Return
gui_wait '.current_frame == 12 and (.typing | not)' "typing 12 + Enter sets frame 12"
gui_frames 3
gui_screenshot seam12 || gui_fail "no screenshot at frame 12"
cmp -s "$GUI_DIR/seam1.png" "$GUI_DIR/seam12.png" && gui_fail "frames 1 and 12 look the same: the seam did not move"
gui_key ctrl+z
gui_wait "(.history.labels | length) == $n or (.history.applied == $n)" "Ctrl+Z undoes the keys"
gui_wait '.animated | index("ball") == null' "after undo the split sphere is not animated"

# --- the incision's opening ---------------------------------------------------------------------------------------
gui_click_item scene.object.cut
gui_wait '.selected == "cut"' "the cut sphere is selected"
gui_key k
gui_wait '.tool == "Incision"' "K picks the Incision tool"
gui_wait '.items["incision_anim.animate"] != null' "the Opening over time panel is shown"
gui_scroll_into_view incision_anim.clear
gui_click_item incision_anim.value_to
gui_wait '.typing' "one click on the second Opening enters text editing"
gui_type "2"
gui_key Return
gui_wait '.typing | not' "Enter applies the opening"
gui_click_item incision_anim.animate
gui_wait_logged '.cmd == "incision.animate" and .object == "cut" and .opening_keys[1][1] == 2.0' \
  "incision.animate logged with the typed opening"
gui_wait '.animated | index("cut") != null' "the cut sphere is animated"
gui_click_item incision_anim.clear
gui_wait_logged '.cmd == "incision.animate" and .object == "cut" and .clear == true' "Clear logs a clear"
gui_wait '.animated | index("cut") == null' "after Clear the cut sphere is not animated"
gui_pass
