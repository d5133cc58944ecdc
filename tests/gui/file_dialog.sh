#!/usr/bin/env bash
# Scene ▸ Load…: a single click on a folder enters it (without crashing the editor); the path field selects its text
# when it gets the keyboard, so typing replaces the old path, and Ctrl+A selects it again.
source "$(dirname "$0")/gui_lib.sh"
mkdir -p "$GUI_WORK/meshes/inner" "$GUI_WORK/other"
gui_start

gui_click_item scene.load
gui_wait '.popups | map(test("file_dialog")) | any' "the Load dialog opens"
gui_click_item "file.entry.meshes/"
gui_wait '.items["file.entry.inner/"] != null' "a single click on meshes/ enters it"
gui_check '.values["file.path"] | endswith("/meshes/")' "the path field shows the folder entered"

# The path field has the keyboard again, its text selected: typing replaces the path shown.
gui_wait '.typing and .active == "file.path"' "the path field has the keyboard"
gui_type "$GUI_WORK/other/"
gui_wait ".values[\"file.path\"] == \"$GUI_WORK/other/\"" "typing replaces the old path (not appended)"
gui_key Return
gui_wait '.items["file.entry.other/"] == null and .items["file.entry.meshes/"] == null' "Enter opens the typed folder"

# Click into the field, Ctrl+A, type: replaced again.
gui_click_item file.path
gui_wait '.typing and .active == "file.path"' "a click gives the path field the keyboard"
gui_frames 2
gui_key ctrl+a
gui_frames 2  # ImGui 1.86 inserts a frame's characters before its shortcuts: type in the next frame
gui_type "$GUI_WORK/meshes/"
gui_wait ".values[\"file.path\"] == \"$GUI_WORK/meshes/\"" "Ctrl+A selects the path so typing replaces it"
gui_key Escape
gui_wait '.popups | length == 0' "Esc closes the dialog"
gui_pass
