#!/usr/bin/env bash
# Object visibility lives in the log (object.visibility): the Scene panel's camera icon takes the sphere out of
# renders and the eye hides a far box in the viewport, each one logged step; Home then frames only what is shown;
# Ctrl+S saves, File ▸ Open of the saved log shows the box still hidden and the sphere still out of renders; undo
# shows the box again.
source "$(dirname "$0")/gui_lib.sh"

mkdir -p "$GUI_WORK/scenes"
cat >"$GUI_WORK/scenes/hide.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"box","name":"b","scale":0.5}
{"cmd":"scene.primitive","kind":"sphere","name":"s","scale":0.5,"translate":[1.5,0,0]}
{"cmd":"scene.primitive","kind":"box","name":"far","scale":0.5,"translate":[1000,0,0]}
LOG
visibility_lines() { gui_session_count '.cmd == "object.visibility"'; }
eye_distance='(.camera.eye as $e | .camera.target as $t | [range(3)] | map(($e[.] - $t[.]) * ($e[.] - $t[.])) | add | sqrt)'

gui_start "$GUI_WORK/scenes/hide.jsonl"
gui_wait '.objects == ["b", "s", "far"] and .history.applied == 3' "the scene is open"
gui_check '.hidden == [] and .render_hidden == []' "everything is shown and rendered"

# The camera icon: the sphere out of renders, one step, still drawn in the viewport.
gui_click_item scene.render.s
gui_wait '.render_hidden == ["s"] and .history.applied == 4' "the camera icon takes the sphere out of renders"
gui_check '.hidden == []' "the sphere stays in the viewport"
jq -e -s 'map(select(.cmd == "object.visibility")) | . == [{"cmd":"object.visibility","object":"s","render":false}]' \
  "$GUI_STATE/session.jsonl" >/dev/null || gui_fail "wrong object.visibility line for the camera icon"

# The eye: the far box hidden in the viewport, one step; Home frames the other two only.
gui_click_item scene.eye.far
gui_wait '.hidden == ["far"] and .history.applied == 5' "the eye hides the far box"
[ "$(visibility_lines)" = 2 ] || gui_fail "expected two object.visibility lines, got $(visibility_lines)"
jq -e -s 'map(select(.cmd == "object.visibility")) | last == {"cmd":"object.visibility","object":"far","viewport":false}' \
  "$GUI_STATE/session.jsonl" >/dev/null || gui_fail "wrong object.visibility line for the eye"
cx="$(gui_q '((.viewport[0] + .viewport[2]) / 2) | floor')"; cy="$(gui_q '((.viewport[1] + .viewport[3]) / 2) | floor')"
gui_move "$cx" "$cy"
gui_frames 1
gui_key Home
gui_wait "$eye_distance < 50" "Home frames the shown objects, not the hidden far box"

# Save, open the saved log: the state comes back from the log.
gui_key ctrl+s
gui_wait '.log | last | test("[Ss]aved")' "Ctrl+S saves the scene"
jq -e -s 'map(select(.cmd == "object.visibility")) | length == 2' "$GUI_WORK/scenes/hide.jsonl" >/dev/null \
  || gui_fail "the saved log lacks the object.visibility lines"
gui_key ctrl+n
gui_wait '.objects == []' "File ▸ New empties the scene"
gui_key ctrl+o
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Open dialog opens, its path field has the keyboard"
gui_type "$GUI_WORK/scenes/hide.jsonl"
gui_key Return
gui_wait '.objects == ["b", "s", "far"] and .hidden == ["far"] and .render_hidden == ["s"]' \
  "after Open the far box is still hidden and the sphere still out of renders" 60

# Undo (the saved view's camera.set first when it is a step of its own) shows the far box again.
for _ in 1 2; do
  [ "$(gui_q '.hidden == []')" = true ] && break
  applied="$(gui_q .history.applied)"
  gui_key ctrl+z
  gui_wait ".history.applied == $((applied - 1))" "Ctrl+Z undoes one step"
done
gui_check '.hidden == [] and .render_hidden == ["s"]' "undo shows the far box; the sphere stays out of renders"
gui_pass
