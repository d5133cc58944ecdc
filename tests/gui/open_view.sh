#!/usr/bin/env bash
# File ▸ Open shows the view the log was saved with (its last camera.set), not one backed off or left where the
# view was moved to.
source "$(dirname "$0")/gui_lib.sh"
mkdir -p "$GUI_WORK/scenes"
ln -s "$GUI_ROOT/assets/data" "$GUI_WORK/data"  # default.jsonl loads ../data/bunny.obj
cp "$GUI_ROOT/assets/scenes/default.jsonl" "$GUI_WORK/scenes/view.jsonl"
gui_start "$GUI_WORK/scenes/view.jsonl"
gui_wait '(.history.labels | length) >= 4' "the scene is open"
cx="$(gui_q '((.viewport[0] + .viewport[2]) / 2) | floor')"; cy="$(gui_q '((.viewport[1] + .viewport[3]) / 2) | floor')"
gui_move "$cx" "$cy"
gui_frames 1
gui_key ctrl+s
gui_wait '.log | last | test("[Ss]aved")' "Ctrl+S saves the scene"
saved="$(jq -c 'select(.cmd == "camera.set") | .eye' "$GUI_WORK/scenes/view.jsonl" | tail -1)"
gui_log "saved eye $saved"
# Move the view away (Home frames everything), then open the saved log again.
gui_key Home
gui_wait ".camera.eye != $saved" "the view moved away" 5
gui_key ctrl+o
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Open dialog opens, its path field has the keyboard"
gui_type "$GUI_WORK/scenes/view.jsonl"
gui_key Return
gui_wait "[.camera.eye, $saved] | transpose | map(.[0] - .[1] | fabs) | max < 1e-6" "the saved view is shown" 60
gui_pass
