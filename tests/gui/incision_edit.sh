#!/usr/bin/env bash
# Editing a drawn incision: after a cut, typing a new Width and Opening in the Incision panel (incision.draw's
# declared size fields) re-runs the cut with them as one undoable step (History keeps one entry, the session log gets
# the re-run line with the typed sizes); an opening the width cannot hold leaves the cut as it was and the Log says
# why; Ctrl+Z then takes the whole cut back. Another object keeps its own sizes.
source "$(dirname "$0")/gui_lib.sh"
cat > "$GUI_DIR/spheres.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"sphere","name":"s"}
{"cmd":"scene.primitive","kind":"sphere","name":"big","scale":3,"translate":[8,0,0]}
{"cmd":"camera.set","eye":[0,0,5],"target":[0,0,0],"fov_deg":45,"viewport":[800,600]}
LOG
gui_start "$GUI_DIR/spheres.jsonl"
gui_wait '(.objects | length) == 2' "the spheres are open"
gui_click_item scene.object.s
gui_wait '.selected == "s"' "sphere selected"
gui_key k
gui_wait '.tool == "Incision"' "K picks the Incision tool"
auto="$(gui_q '.values["incision.opening"]')"
x="$(gui_q '.object_px.s[0] | floor')"
y=$(($(gui_q '.object_px.s[1] | floor') + 40))
n="$(gui_q '.history.applied')"
gui_move $((x - 60)) "$y"
gui_frames 1
xdotool mousedown 1
gui_frames 2
for i in 1 2 3 4 5 6; do
  gui_move $((x - 60 + 20 * i)) $((y + 2 * i))
  gui_frames 1
done
xdotool mouseup 1
gui_wait ".history.applied == $((n + 1))" "one history entry for the cut" 60
gui_wait_logged '.cmd == "incision.draw" and .object == "s"' "incision.draw logged"
before="$(gui_q '.object_px.s')"

gui_click_item incision.width
gui_wait '.typing' "one click on Width enters text editing"
gui_type "0.3"
gui_key Return
gui_wait_logged '.cmd == "incision.draw" and .object == "s" and .width == 0.3' "the cut re-run with the typed width" 60
gui_wait ".history.applied == $((n + 1))" "still one history entry: the re-run replaced the cut"
gui_check '(.history.labels | length) == '"$((n + 1))" "no redo tail left behind"
gui_click_item incision.opening
gui_wait '.typing' "one click on Opening enters text editing"
gui_type "0.05"
gui_key Return
gui_wait_logged '.cmd == "incision.draw" and .object == "s" and .width == 0.3 and .opening == 0.05' \
  "the cut re-run with the typed opening, keeping the typed width" 60
gui_wait ".history.applied == $((n + 1))" "still one history entry"
# An opening the width cannot hold (limited first to 0.2 × the sphere's diagonal): the cut stays as it was and the Log
# says why.
gui_click_item incision.opening
gui_wait '.typing' "Opening again"
gui_type "5"
gui_key Return
gui_wait '.log | map(select(test("Incision opening 5: Limited to [0-9.]+: the opening is at most 0.2 x"))) | length == 1' \
  "the typed opening is limited to what the sphere takes (its declared object_size), and the Log says so"
gui_wait '.log | map(select(test("too wide for width"))) | length == 1' "the Log says why the edit cannot re-run the cut" 60
gui_wait ".history.applied == $((n + 1)) and (.history.labels[-1] | test(\"opening 0.05\"))" \
  "the previous cut is back (still one entry)"
gui_wait '(.values["incision.opening"] | tonumber) == 0.05' "the panel shows the opening of the cut back in place"
gui_shot recut

# The big sphere keeps its own sizes: relative to its size, not the small sphere's typed ones.
gui_click_item scene.object.big
gui_wait '.selected == "big"' "the big sphere selected"
gui_wait '(.values["incision.opening"] | tonumber) > ('"$auto"' | tonumber) * 2' "the big sphere's opening is its own (auto)"

gui_key ctrl+z
gui_wait ".history.applied == $n" "Ctrl+Z takes the whole cut back"
gui_pass
