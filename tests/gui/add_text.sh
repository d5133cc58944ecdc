#!/usr/bin/env bash
# Scene ▸ Add ▸ Text… in the real editor through real X input: the dialog opens with the text field taking the keys
# (its text selected);
# typed text and a typed size give one scene.text line with them (default depth), one undoable step, the new object
# selected; Esc in a second dialog cancels with nothing logged; Ctrl+Z removes the text.
source "$(dirname "$0")/gui_lib.sh"
printf '%s\n' '{"cmd":"scene.primitive","kind":"teapot","name":"teapot"}' >"$GUI_WORK/teapot.jsonl"
gui_start "$GUI_WORK/teapot.jsonl"
gui_wait '.objects == ["teapot"] and .history.applied == 1' "the teapot scene is open"

gui_click_item scene.add
gui_wait '.items["scene.add.text"] != null' "Add opens its menu with Text..."
gui_click_item scene.add.text
gui_wait '.popups | map(test("Add text")) | any' "Text... opens the Add text dialog"
gui_wait '.typing == true' "the dialog's text field takes the keys"
gui_type "CGGC"  # the field opens with its text selected: typing replaces it
gui_click_item scene.text.size
gui_frames 4  # press, release and the text mode's opening: the Text field's typing flag is still up meanwhile
gui_wait '.active == "scene.text.size" and .typing == true' "one click on Size enters text editing"
gui_type "0.4"
gui_key Tab
gui_frames 2
gui_shot add_text_dialog
gui_click_item scene.text.add
gui_wait '.objects == ["teapot", "text"] and .selected == "text"' "Add makes the text object and selects it" 60
gui_wait_logged '.cmd == "scene.text" and .text == "CGGC" and .size == 0.4 and .depth == 0.25 and .name == "text"' \
  "one scene.text line with the typed text and size"
gui_check '.history.applied == 2' "one history step"
gui_frames 2
gui_shot add_text_done

# A second dialog cancelled with Esc adds nothing.
gui_click_item scene.add
gui_wait '.items["scene.add.text"] != null' "Add opens its menu again"
gui_click_item scene.add.text
gui_wait '.popups | map(test("Add text")) | any' "the dialog opens again"
gui_key Escape
gui_wait '(.popups | map(test("Add text")) | any) | not' "Esc closes the dialog"
gui_frames 2
gui_check '.history.applied == 2 and .objects == ["teapot", "text"]' "Esc added nothing"
[ "$(gui_session_count '.cmd == "scene.text"')" = 1 ] || gui_fail "a cancelled dialog logged a scene.text"

gui_key ctrl+z
gui_wait '.objects == ["teapot"] and .history.applied == 1' "Ctrl+Z removes the text"
gui_pass
