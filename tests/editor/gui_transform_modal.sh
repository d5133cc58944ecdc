#!/usr/bin/env bash
# The real editor under Xvfb driven with real X input (xdotool, XTEST): click the box to select it, G X 1.5 Enter →
# session.jsonl holds exactly one object.transform with translate [1.5,0,0]; G Y 3 Esc → still one; Ctrl+Z → an
# edit.undo line; a click in the Scene panel's Location x field, G 2 Enter → one object.transform with only translate
# [2,0,0] (G went into the field, not to the modal). Run it under tests/with_xvfb.sh (ctest: editor.gui_transform_modal):
#   with_xvfb.sh 1280x900x24 gui_transform_modal.sh path/to/trispline
# Keys are sent in bursts (xdotool's 12 ms between keys), so at 2-4 fps several arrive within one frame, as typed by
# a fast user on software GL. Exits 0 on success; prints the elapsed time.
set -euo pipefail
trispline="$1"
start=$(date +%s.%N)
work="$(mktemp -d)"
export TRISPLINE_STATE_DIR="$work/state"
log="$TRISPLINE_STATE_DIR/session.jsonl"
editor_pid=""
cleanup() {
  [[ -n "$editor_pid" ]] && kill "$editor_pid" 2>/dev/null && wait "$editor_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  echo "--- session.jsonl:" >&2
  cat "$log" >&2 2>/dev/null || true
  echo "--- editor output:" >&2
  tail -20 "$work/editor.out" >&2 2>/dev/null || true
  exit 1
}
count() {  # lines of session.jsonl containing $1 (0 while it does not exist)
  local n
  n=$(grep -c -- "$1" "$log" 2>/dev/null || true)
  echo "${n:-0}"
}
# Waits up to $1 seconds for `grep -c $2 session.jsonl` to reach $3.
wait_count() {
  local deadline=$(( $(date +%s) + $1 ))
  while (( $(date +%s) < deadline )); do
    (( $(count "$2") >= $3 )) && return 0
    sleep 0.3
  done
  return 1
}

# One box at the origin; it is the first row of the Scene panel (the right column, x 950..1280 in a 1280-wide window,
# the row below the Load / Add / Remove buttons at y ~82).
printf '%s\n' '{"cmd":"scene.primitive","kind":"box","name":"b"}' >"$work/scene.jsonl"
# On a machine shared with other Xvfb users the first connection to a fresh server fails now and then (see
# with_xvfb.sh): start again, up to three times, when the editor could not open its window.
for attempt in 1 2 3; do
  "$trispline" edit "$work/scene.jsonl" --no-recover --width 1280 --height 900 >"$work/editor.out" 2>&1 &
  editor_pid=$!
  deadline=$(( $(date +%s) + 120 ))
  while (( $(date +%s) < deadline )) && kill -0 "$editor_pid" 2>/dev/null && (( $(count '"scene.primitive"') < 1 )); do
    sleep 0.3
  done
  (( $(count '"scene.primitive"') >= 1 )) && break
  kill "$editor_pid" 2>/dev/null || true
  wait "$editor_pid" 2>/dev/null || true
  editor_pid=""
  grep -q "no window can be created" "$work/editor.out" || break
  echo "gui_transform_modal: the editor could not open its window (attempt $attempt), again" >&2
  sleep 2
done
[[ -n "$editor_pid" ]] || fail "the editor did not start"
(( $(count '"scene.primitive"') >= 1 )) || fail "the editor did not open the scene"
wid=$(xdotool search --sync --onlyvisible --name '^trispline' | head -1)
[[ -n "$wid" ]] || fail "no editor window"
xdotool windowfocus --sync "$wid" 2>/dev/null || xdotool windowfocus "$wid"
sleep 2  # a few frames at software-GL speed after the "Working…" frame of the open

# Select: a click (press and release) on the box's row in the Scene panel.
xdotool mousemove --window "$wid" 1060 82
sleep 0.5
xdotool click 1
sleep 1.5

# G X 1.5 Enter: exactly one object.transform with the typed translation.
xdotool key g x 1 period 5 Return
wait_count 30 '"object.transform"' 1 || fail "no object.transform after G X 1.5 Enter (was the box selected?)"
sleep 1
[[ $(count '"object.transform"') == 1 ]] || fail "more than one object.transform for one confirm"
line=$(grep '"object.transform"' "$log")
python3 - "$line" <<'EOF' || fail "wrong object.transform: $line"
import json, sys
j = json.loads(sys.argv[1])
assert j["object"] == "b", j
assert j["translate"] == [1.5, 0, 0], j
assert j["rotate_deg"] == [0, 0, 0] and j["scale"] == 1, j
EOF

# G Y 3 Esc: cancelled, nothing more in the log.
lines_before=$(wc -l <"$log")
xdotool key g y 3 Escape
sleep 2
[[ $(count '"object.transform"') == 1 ]] || fail "Esc did not cancel: another object.transform"
[[ $(wc -l <"$log") == "$lines_before" ]] || fail "Esc cancel wrote to the session log"

# Ctrl+Z undoes the transform (an edit.undo line follows it).
xdotool key ctrl+z
wait_count 30 '"edit.undo"' 1 || fail "Ctrl+Z wrote no edit.undo"
[[ $(tail -1 "$log") == *'"edit.undo"'* ]] || fail "the last line is not edit.undo"

# The Scene panel's Location x field (Transform section, bottom of the Scene panel: x ~1020..1098, y ~337): one click
# enters text; G typed there is not a grab (the field refuses the letter), 2 Enter sets x = 2: one object.transform
# with only "translate" (the modal would write all three fields).
xdotool mousemove --window "$wid" 1058 337
sleep 0.3
xdotool click 1
sleep 1.5
xdotool key g 2 Return
wait_count 30 '"object.transform"' 2 || fail "no object.transform from the Location field"
sleep 1
[[ $(count '"object.transform"') == 2 ]] || fail "the Location field ran more than one object.transform"
line=$(grep '"object.transform"' "$log" | tail -1)
python3 - "$line" <<'EOF' || fail "wrong object.transform from the Location field: $line"
import json, sys
j = json.loads(sys.argv[1])
assert j["object"] == "b" and j["translate"] == [2, 0, 0], j
assert "rotate_deg" not in j and "scale" not in j, j
EOF
kill -0 "$editor_pid" 2>/dev/null || fail "the editor died"

end=$(date +%s.%N)
awk -v a="$start" -v b="$end" 'BEGIN { printf "gui_transform_modal: OK in %.1f s\n", b - a }'
