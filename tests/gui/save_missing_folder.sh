#!/usr/bin/env bash
# File ▸ Save As with a folder that does not exist typed in the path field: refused with an error, nothing written
# (in particular, nothing saved into the folder listed).
source "$(dirname "$0")/gui_lib.sh"
gui_start
gui_key ctrl+shift+s
gui_wait '.popups | map(test("file_dialog")) | any' "the Save dialog opens"
gui_click_item file.path
gui_wait '.typing and .active == "file.path"' "the path field has the keyboard"
gui_type "$GUI_WORK/missing/"
gui_wait ".values[\"file.path\"] == \"$GUI_WORK/missing/\"" "the folder typed"
gui_click_item file.name
gui_wait '.typing and .active == "file.name"' "the name field has the keyboard"
gui_type "scene"
gui_key Return
gui_wait '.values["file.error"] | test("no such folder")' "the Save is refused with an error"
gui_frames 2
gui_check '.popups | map(test("file_dialog")) | any' "the dialog stays open"
found="$(find "$GUI_WORK" -name '*.jsonl' | head -1)"
[ -z "$found" ] || gui_fail "a scene was written: $found"
[ ! -e "$GUI_WORK/missing" ] || gui_fail "the missing folder was created"
gui_pass
