#!/usr/bin/env bash
# Scene ▸ Load… of a file with points and lines beside its faces: refused with the counts in the Log (nothing of a
# file is dropped silently), the scene unchanged; with the dialog's "Leave out points and lines" on, the faces load
# as one undoable scene.load with "loose":"ignore" and the Log says what was left out.
source "$(dirname "$0")/gui_lib.sh"
mkdir -p "$GUI_WORK/meshes"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nl 1 3\nl 2 4\np 1\n' > "$GUI_WORK/meshes/mixed.obj"
gui_start
objects_before="$(gui_q '.objects | length')"

gui_click_item scene.load
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens, its path field has the keyboard"
gui_check '.values["file.option"] == "off"' "Leave out points and lines is off by default"
gui_type "$GUI_WORK/meshes/mixed.obj"
gui_key Return
gui_wait '.log | last | test("1 point and 2 line elements besides its 2 faces")' "the file is refused, naming the counts" 30
gui_check ".objects | length == $objects_before" "the scene is unchanged"

gui_click_item scene.load
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens again"
gui_click_item file.option
gui_wait '.values["file.option"] == "on"' "a click turns the option on"
gui_click_item file.path
gui_wait '.typing and .active == "file.path"' "the path field has the keyboard"
gui_type "$GUI_WORK/meshes/mixed.obj"
gui_key Return
gui_wait ".objects | length == $objects_before + 1" "the faces load" 30
gui_check '.log | map(test("left out 1 point and 2 lines")) | any' "the Log says what was left out"
[ "$(gui_session_count '.cmd == "scene.load" and .loose == "ignore"')" = 1 ] || gui_fail "one scene.load with loose ignore in the session log"
gui_key ctrl+z
gui_wait ".objects | length == $objects_before" "Ctrl+Z takes it back"
gui_pass
