#!/usr/bin/env bash
# File ▸ Open of a log whose second line fails (a mesh that does not exist): the Log names LOG:LINE, and the open
# scene, its history, its document and its modified flag stay as they were — no half-opened scene for a later Save to
# write over the good file.
source "$(dirname "$0")/gui_lib.sh"
mkdir -p "$GUI_WORK/scenes"
printf '%s\n' '{"cmd":"scene.primitive","kind":"plane","name":"ground"}' >"$GUI_WORK/scenes/good.jsonl"
printf '%s\n' '{"cmd":"scene.primitive","kind":"sphere","name":"ball"}' \
  '{"cmd":"scene.load","path":"no_such_mesh.obj","name":"ghost"}' \
  '{"cmd":"scene.primitive","kind":"box","name":"crate"}' >"$GUI_WORK/scenes/bad.jsonl"
gui_start "$GUI_WORK/scenes/good.jsonl"
gui_wait '(.history.labels | length) >= 1 and .modified == false' "the good scene is open, unmodified"
objects="$(gui_q '.objects | tojson')"
labels="$(gui_q '.history.labels | tojson')"
document="$(gui_q '.document')"
gui_log "open: $document, objects $objects"

gui_key ctrl+o
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Open dialog opens, its path field has the keyboard"
gui_type "$GUI_WORK/scenes/bad.jsonl"
gui_key Return
gui_wait '.log | map(test("^Open failed, the current scene is kept: .*bad.jsonl:2")) | any' "the Log says the scene is kept and names the failing line (bad.jsonl:2)" 60
gui_frames 2
gui_check ".objects == $objects" "the scene's objects are unchanged (no ball from line 1)"
gui_check ".history.labels == $labels" "the history is unchanged"
gui_check ".document == \"$document\" and .modified == false" "the document is still the good file, unmodified"
# The next Open goes straight to its dialog: nothing to save.
gui_key ctrl+o
gui_wait '(.popups | map(test("file_dialog")) | any)' "Open again shows the file dialog, not 'Save changes?'"
gui_check '.popups | map(test("Save changes")) | any | not' "no 'Save changes?' prompt"
gui_key Escape
gui_pass
