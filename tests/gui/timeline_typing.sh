#!/usr/bin/env bash
# Number fields take typed values at software-GL frame rates (3 fps here): one click enters text editing with the
# value selected. The current frame (view state) and the range end (anim.timeline, logged).
source "$(dirname "$0")/gui_lib.sh"
gui_start
gui_click_item timeline.frame
gui_wait '.typing' "one click on the frame field enters text editing"
gui_type "7"
gui_key Return
gui_wait '.current_frame == 7 and (.typing | not)' "typing 7 + Enter sets frame 7"

gui_click_item timeline.end
gui_wait '.typing' "one click on End enters text editing"
gui_type "60"
gui_key Return
gui_wait '.typing | not' "Enter leaves the field"
gui_frames 2
[ "$(gui_session_count '.cmd == "anim.timeline" and .end == 60')" = 1 ] || gui_fail "no anim.timeline with end 60 logged"
gui_pass
