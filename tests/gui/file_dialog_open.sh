#!/usr/bin/env bash
# The file dialog at software-GL frame rates: Load…'s Open button lies inside the dialog (its long filter of mesh and
# volume extensions goes on a line of its own); a double-click on a file opens it, and so does a click then Enter;
# Save As from the shipped default scene offers the document's own name in the folder the editor started in (not the
# shipped scenes' folder) — and still does after a load from elsewhere, while Load starts in the folder it last read.
source "$(dirname "$0")/gui_lib.sh"
mkdir -p "$GUI_WORK/meshes"
cat > "$GUI_WORK/meshes/tetra.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
OBJ
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.objects | length) == 2' "the default scene opens"

gui_key ctrl+shift+s
gui_wait '.popups | map(test("file_dialog")) | any' "Save As opens"
gui_wait '.values["file.name"] == "default.jsonl"' "Save As offers the document's own name, with .jsonl"
gui_check ".values[\"file.path\"] == \"$GUI_WORK/\"" "Save As starts where the editor started, not in assets/scenes"
gui_key Escape
gui_wait '.popups | length == 0' "Esc closes the dialog"

gui_click_item scene.load
gui_wait '.popups | map(test("file_dialog")) | any' "the Load dialog opens"
gui_wait '.items["file.dialog"] != null and .items["file.ok"] != null' "the dialog and its Open button are drawn"
gui_check '.items["file.ok"][2] <= .items["file.dialog"][2] - 4 and .items["file.cancel"][2] <= .items["file.dialog"][2] - 4' \
  "Open and Cancel lie inside the dialog at its default size"
gui_click_item "file.entry.meshes/"
gui_wait '.items["file.entry.tetra.obj"] != null' "a click enters meshes/"
read -r x y <<<"$(gui_item_center file.entry.tetra.obj)"
gui_move "$x" "$y"
gui_frames 1
gui_log "double-click tetra.obj at $x $y"
xdotool click --repeat 2 --delay 80 1
gui_wait '(.popups | length) == 0 and (.objects | length) == 3' "a double-click opens the file" 60

gui_click_item scene.load
gui_wait '.items["file.entry.tetra.obj"] != null' "Load starts in the folder of the last file loaded"
gui_click_item file.entry.tetra.obj
gui_wait '.values["file.path"] | endswith("/meshes/tetra.obj")' "a click selects the file"
gui_key Return
gui_wait '(.popups | length) == 0 and (.objects | length) == 4' "Enter opens the selected file" 60

gui_key ctrl+shift+s
gui_wait '.popups | map(test("file_dialog")) | any' "Save As opens again"
gui_check ".values[\"file.path\"] == \"$GUI_WORK/\"" "Save As still starts where the editor started (a load is not a save)"
gui_key Escape
gui_pass
