#!/usr/bin/env bash
# An idle editor draws nothing (`trispline edit` without --idle-fps): once the default scene is open and the pointer
# rests, the frame count stays put; moving the pointer draws at once; a pointer resting on a widget still gets its
# tooltip (frames go on for a second after the last input); a click on Play draws every frame of the playback
# without further input, and Pause lets the editor fall idle again.
GUI_IDLE_FPS=0
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"

# gui_idle_check WHAT: no frame is drawn for 3 s once a 1.5 s settling time has passed.
gui_idle_check() {
  local f1 f2
  gui_pause 1.5
  f1="$(gui_frame)"
  gui_pause 3
  f2="$(gui_frame)"
  [ "$f1" = "$f2" ] || gui_fail "$1: the idle editor drew $((f2 - f1)) frames in 3 s"
  gui_log "ok: $1: no frame drawn in 3 s (frame $f2)"
}

read -r vx vy <<<"$(gui_q '.viewport | "\(((.[0] + .[2]) / 2) | floor) \(((.[1] + .[3]) / 2) | floor)"')"
gui_move "$vx" "$vy"
gui_idle_check "after opening"
before="$(gui_frame)"
gui_move $((vx + 40)) $((vy + 20))
gui_wait ".frame > $before" "moving the pointer draws a frame" 5

# A tooltip appears under a resting pointer without any further event.
read -r tx ty <<<"$(gui_item_center timeline.frame)"
gui_move "$tx" "$ty"
gui_wait '.tooltip' "the frame field's tooltip appears under the resting pointer" 5
gui_idle_check "with the tooltip shown"

# Playback draws without input; pausing lets the editor fall idle.
gui_key space
gui_wait '.current_frame > 3' "playback advances the frame without input" 20
gui_key space
gui_idle_check "after pausing playback"
gui_pass
