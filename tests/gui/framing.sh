#!/usr/bin/env bash
# Home frames the scene into the part of the viewport the panels leave visible (not the window's centre).
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.objects | length) >= 2' "the default scene is open"
# The pointer over the viewport, so the key reaches it.
gui_move "$(gui_q '((.viewport[0] + .viewport[2]) / 2) | floor')" "$(gui_q '((.viewport[1] + .viewport[3]) / 2) | floor')"
gui_frames 1
gui_key Home
gui_frames 2
cond='((.scene_center_px[0] - (.viewport[0] + .viewport[2]) / 2) | fabs) < 4 and
      ((.scene_center_px[1] - (.viewport[1] + .viewport[3]) / 2) | fabs) < 4'
gui_wait "$cond" "the scene's centre is the visible viewport's centre"
gui_pass
