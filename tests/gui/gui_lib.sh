#!/usr/bin/env bash
# GUI test harness: drives the real `trispline` editor through real X input (xdotool) under the private Xvfb of
# tests/with_xvfb.sh, at a throttled frame rate, and asserts on its probe file (--gui-probe, editor/gui_probe.h) and
# its session log. A test is a bash script that sources this file:
#
#   source "$(dirname "$0")/gui_lib.sh"        # needs TRISPLINE (the executable) and GUI_OUT (a results folder)
#   gui_start "$GUI_ROOT/assets/scenes/default.jsonl"      # editor at GUI_FPS (default 3) frames per second; waits for it
#   gui_click_item scene.load                   # a widget named with ui::probe::item() in the editor
#   gui_wait '.popups | length > 0' "the Load dialog opens"   # a jq condition on the probe JSON, with a timeout
#   gui_pass                                    # quits the editor; exit 0
#
# On a failed check the editor's screenshot (F12), the probe JSON and the session log are saved under
# $GUI_OUT/<test>/ and their paths printed; the test exits 1. The editor dying is a failure at the next check.
set -euo pipefail

: "${TRISPLINE:?set TRISPLINE to the trispline executable}"
: "${GUI_OUT:?set GUI_OUT to a folder for failure artefacts}"
GUI_FPS="${GUI_FPS:-3}"
# Frames a second while nothing changes: the waits below count frames, so the tests keep the editor drawing
# (tests/gui/idle.sh sets 0, the editor's default, and checks that an idle editor draws nothing).
GUI_IDLE_FPS="${GUI_IDLE_FPS:-$GUI_FPS}"
GUI_TIMEOUT="${GUI_TIMEOUT:-20}"  # seconds a gui_wait may take by default
# Seconds for the window and its first frames: the first frames compile the shaders on llvmpipe, and the log being
# opened replays on a worker beside them — 8 s to frame 3 with tests/logs/ddm_follow.jsonl on an idle 2-core machine
# when Open still replayed on the UI thread, 22 s beside four busy processes (ctest runs the farm tests and another
# window test next to it).
GUI_START_TIMEOUT="${GUI_START_TIMEOUT:-90}"
GUI_TEST="$(basename "${0%.sh}")"
GUI_DIR="$GUI_OUT/$GUI_TEST"
rm -rf "$GUI_DIR"
mkdir -p "$GUI_DIR"
GUI_STATE="$GUI_DIR/state"   # TRISPLINE_STATE_DIR: session.jsonl lands here
GUI_WORK="$GUI_DIR/work"     # the editor's current folder (F12 screenshots land here)
GUI_PROBE="$GUI_DIR/probe.json"
mkdir -p "$GUI_STATE" "$GUI_WORK"
# Debian's Python (python3-numpy, python3-pil from scripts/test_packages.txt), whatever python3 comes first on PATH.
GUI_PYTHON="${GUI_PYTHON:-/usr/bin/python3}"
GUI_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
GUI_PID=""
GUI_WID=""

gui_log() { echo "[$GUI_TEST $(date +%T)] $*"; }

# Saves the artefacts and fails the test.
gui_fail() {
  set +e +o pipefail
  echo "FAIL: $GUI_TEST: $*" >&2
  echo "$*" >"$GUI_DIR/failure.txt"
  if gui_alive; then
    gui_screenshot failure 6 && echo "  screenshot: $GUI_DIR/failure.png" >&2
  else
    echo "  the editor is not running (exit status ${GUI_EXIT:-?})" >&2
  fi
  [ -f "$GUI_PROBE" ] && cp "$GUI_PROBE" "$GUI_DIR/failure_probe.json" && echo "  probe: $GUI_DIR/failure_probe.json" >&2
  [ -f "$GUI_STATE/session.jsonl" ] && echo "  session log: $GUI_STATE/session.jsonl" >&2
  echo "  editor output: $GUI_DIR/editor.log" >&2
  gui_kill
  exit 1
}

# The editor's finished F12 screenshots in $GUI_WORK (it writes NAME.tmp.png, then renames it).
gui_screenshots() { find "$GUI_WORK" -maxdepth 1 -name 'trispline-screenshot-*.png' ! -name '*.tmp*'; }

# gui_screenshot NAME [SECONDS]: presses F12, waits (default 20 s) for the editor to finish writing the new
# screenshot and copies it to $GUI_DIR/NAME.png. Returns 1 when none appears.
gui_screenshot() {
  local before newest tries=$(( ${2:-20} * 5 ))
  before="$(gui_screenshots | wc -l)"
  xdotool key F12 2>/dev/null || return 1
  for _ in $(seq 1 "$tries"); do
    [ "$(gui_screenshots | wc -l)" -gt "$before" ] && break
    sleep 0.2
  done
  [ "$(gui_screenshots | wc -l)" -gt "$before" ] || return 1
  newest="$(gui_screenshots | sort -V | tail -1)"
  cp "$newest" "$GUI_DIR/$1.png"
}

# gui_shot NAME: an F12 screenshot copied to $GUI_DIR/NAME.png, or the test fails.
gui_shot() { gui_screenshot "$1" || gui_fail "no screenshot written for $1"; }

# gui_view_shading Solid|Material|Automatic: View ▸ Shading ▸ that mode through the menus, then 3 frames.
gui_view_shading() {
  gui_click_item menu.View
  gui_wait '.items["menu.Shading"] != null' "the View menu opens"
  gui_click_item menu.Shading
  gui_wait ".items[\"menu.$1\"] != null" "the Shading menu opens"
  gui_click_item "menu.$1"
  gui_wait '.popups | length == 0' "the menu closes after picking $1"
  gui_frames 3
}

gui_alive() { [ -n "$GUI_PID" ] && kill -0 "$GUI_PID" 2>/dev/null; }

gui_kill() {
  if gui_alive; then kill "$GUI_PID" 2>/dev/null || true; wait "$GUI_PID" 2>/dev/null || true; fi
  GUI_PID=""
}

# gui_start [EDITOR ARGS...]: starts `trispline edit --no-recover` with the probe and the frame-rate cap, waits for
# its window and its first frames. The editor runs in $GUI_WORK (its file dialogs start there): give absolute paths
# ($GUI_ROOT is the repository root).
gui_start() {
  (cd "$GUI_WORK" && exec env TRISPLINE_STATE_DIR="$GUI_STATE" \
     "$TRISPLINE" edit --no-recover --gui-probe "$GUI_PROBE" --max-fps "$GUI_FPS" --idle-fps "$GUI_IDLE_FPS" --width 1280 --height 800 "$@" \
     >"$GUI_DIR/editor.log" 2>&1) &
  GUI_PID=$!
  gui_log "editor pid $GUI_PID at $GUI_FPS fps: $*"
  local i
  for i in $(seq 1 $((GUI_START_TIMEOUT * 10))); do
    GUI_WID="$(xdotool search --pid "$GUI_PID" --name trispline 2>/dev/null | head -1 || true)"
    [ -n "$GUI_WID" ] && [ -f "$GUI_PROBE" ] && break
    if ! gui_alive; then
      # A fresh Xvfb now and then refuses the first connection on a loaded 2-core machine (tests/with_xvfb.sh).
      if [ -z "${GUI_RETRIED:-}" ] && grep -q "no window can be created" "$GUI_DIR/editor.log"; then
        GUI_RETRIED=1; GUI_PID=""; sleep 1; gui_start "$@"; return
      fi
      gui_fail "the editor exited at start"
    fi
    sleep 0.1
  done
  [ -n "$GUI_WID" ] || gui_fail "no editor window after ${GUI_START_TIMEOUT}s"
  xdotool windowmove "$GUI_WID" 0 0 2>/dev/null || true
  xdotool windowfocus "$GUI_WID" 2>/dev/null || true
  gui_wait '.frame >= 3' "the editor draws frames" "$GUI_START_TIMEOUT"
}

# gui_q JQ: the jq expression evaluated on the current probe (raw output).
gui_q() { jq -r "$1" "$GUI_PROBE" 2>/dev/null; }

# gui__frame_of TEXT: sets GUI__FRAME to the probe's frame counter read without jq, when the key "frame" occurs
# exactly once in the probe JSON; returns 1 otherwise (the caller asks jq).
gui__frame_of() {
  [[ $1 =~ \"frame\":([0-9]+) ]] || return 1
  local n="${BASH_REMATCH[1]}" rest="${1#*\"frame\":}"
  [[ $rest != *\"frame\":* ]] || return 1
  GUI__FRAME="$n"
}

# gui_frame: the number of frames the editor has drawn.
gui_frame() {
  local text=""
  IFS= read -r text <"$GUI_PROBE" 2>/dev/null || true
  if gui__frame_of "$text"; then echo "$GUI__FRAME"; else gui_q .frame; fi
}

# A 0.1 s pause without a process: a read that times out on a pipe nobody writes to.
exec {GUI_PAUSE_FD}<> <(:)
gui_pause() { read -r -t "${1:-0.1}" -u "$GUI_PAUSE_FD" _ || true; }

# gui_wait JQ WHAT [SECONDS]: waits until the jq condition holds on the probe; fails with WHAT otherwise. The probe is
# read with a shell builtin every 0.1 s and jq runs only when the editor wrote a new one (at most once a frame): a
# jq start costs ~25 ms of CPU, ten a second would cost a quarter of a core beside the editor.
gui_wait() {
  local cond="$1" what="$2" limit="${3:-$GUI_TIMEOUT}" end text seen="" want
  end=$((EPOCHSECONDS + limit))
  while true; do
    if ! gui_alive; then
      GUI_EXIT=0
      wait "$GUI_PID" 2>/dev/null || GUI_EXIT=$?
      GUI_PID=""
      gui_fail "the editor died (exit status $GUI_EXIT), waiting for: $what"
    fi
    text=""
    IFS= read -r text <"$GUI_PROBE" 2>/dev/null || true
    if [ -n "$text" ] && [ "$text" != "$seen" ]; then
      seen="$text"
      want=""
      [[ $cond =~ ^\.frame\ \>=\ ([0-9]+)$ ]] && want="${BASH_REMATCH[1]}"
      if [ -n "$want" ] && gui__frame_of "$text"; then  # most waits (gui_frames): without jq
        ((GUI__FRAME >= want)) && return 0
      elif [ "$(jq -r "($cond) == true" <<<"$text" 2>/dev/null)" = "true" ]; then
        return 0
      fi
    fi
    [ "$EPOCHSECONDS" -ge "$end" ] && gui_fail "timed out after ${limit}s waiting for: $what ($cond)"
    gui_pause
  done
}

# gui_check JQ WHAT: the condition must hold now.
gui_check() { gui_wait "$1" "$2" 0; }

# gui_frames N: waits until N more frames were drawn. The first may have read its input before the last X event was
# sent: wait 2 when one whole frame must have seen it (keys ImGui handles one per frame, a press before a move).
gui_frames() {
  local now
  now="$(gui_frame)"
  gui_wait ".frame >= $((now + $1))" "$1 more frames"
}

# gui_item_center NAME: "x y" of the named widget's centre once it is on screen and has stopped moving (a window
# appearing is placed in its first frames).
gui_item_center() {
  local key=".items[\"$1\"]" r1 r2
  gui_wait "$key != null" "widget $1 on screen"
  r1="$(gui_q "$key")"
  while true; do
    gui_frames 1
    r2="$(gui_q "$key")"
    [ "$r1" = "$r2" ] && [ "$r2" != null ] && break
    r1="$r2"
  done
  gui_q "$key | \"\(((.[0] + .[2]) / 2) | floor) \(((.[1] + .[3]) / 2) | floor)\""
}

gui_move() { xdotool mousemove --window "$GUI_WID" "$1" "$2"; }
# gui_scroll_into_view NAME [PANEL]: turns the mouse wheel over the docked panel (default the Tool panel,
# "panel.tool") holding the named widget until the widget lies inside the panel's visible part, as a user scrolls.
gui_scroll_into_view() {
  local key=".items[\"$1\"]" panel=".items[\"${2:-panel.tool}\"]" i
  gui_wait "$key != null and $panel != null" "widget $1 and its panel on screen"
  for ((i = 0; i < 20; ++i)); do
    [ "$(gui_q "$key[3] < $panel[3] - 4")" = true ] && return 0
    gui_move "$(gui_q "(($panel[0] + $panel[2]) / 2) | floor")" "$(gui_q "(($panel[1] + $panel[3]) / 2) | floor")"
    xdotool click 5 click 5
    gui_frames 2
  done
  gui_fail "widget $1 stays below the panel's visible part"
}
# gui_click X Y [BUTTON]: moves there, lets one frame see the hover, clicks.
gui_click() {
  gui_move "$1" "$2"
  gui_frames 1
  xdotool click "${3:-1}"
}
gui_click_item() {
  local xy x y
  xy="$(gui_item_center "$1")"
  gui_log "click $1 at $xy"
  # A user cannot click what lies outside the window (a widget pushed past a panel's edge).
  read -r x y <<<"$xy"
  ((x >= 0 && x < 1280 && y >= 0 && y < 800)) || gui_fail "widget $1 is outside the 1280×800 window (centre $xy)"
  # shellcheck disable=SC2086
  gui_click $xy "${2:-1}"
}
# gui_drag X0 Y0 X1 Y1 [MODIFIER]: a left-button drag in a few steps, optionally holding ctrl / shift / alt.
gui_drag() {
  local mod="${5:-}" i
  gui_move "$1" "$2"
  gui_frames 1
  [ -n "$mod" ] && xdotool keydown "$mod"
  xdotool mousedown 1
  gui_frames 2
  for i in 1 2 3 4; do
    gui_move $(($1 + ($3 - $1) * i / 4)) $(($2 + ($4 - $2) * i / 4))
    gui_frames 1
  done
  xdotool mouseup 1
  [ -n "$mod" ] && xdotool keyup "$mod"
  gui_frames 1
}
gui_key() { gui_log "key $*"; xdotool key --delay 30 "$@"; }
gui_type() { gui_log "type '$1'"; xdotool type --delay 30 "$1"; }

# gui_session_count JQ: how many lines of the session log satisfy the jq condition (e.g. '.cmd == "scene.load"').
gui_session_count() { jq -c "select($1)" "$GUI_STATE/session.jsonl" 2>/dev/null | wc -l; }

# gui_wait_logged JQ MESSAGE [FRAMES]: waits (60 frames by default) until some session-log line satisfies JQ.
gui_wait_logged() {
  local i
  for ((i = 0; i < ${3:-60}; ++i)); do
    [ "$(gui_session_count "$1")" -ge 1 ] && { gui_log "ok: $2"; return 0; }
    gui_frames 1
  done
  gui_fail "$2"
}

# Quits the editor (kills it: the session log is flushed line by line) and passes.
gui_pass() {
  gui_alive || gui_fail "the editor is gone at the end"
  gui_kill
  gui_log "PASS"
  exit 0
}

trap 'gui_kill' EXIT

# The default scene open (gui_start'ed with assets/scenes/default.jsonl): selects the teapot in the Scene panel, puts
# the pointer over it and picks the Tile Paint tool (T), waiting until the panel shows its Fill estimate.
gui_teapot_tile_paint() {
  gui_wait '(.history.labels | length) >= 4' "the default scene is open"
  gui_click_item scene.object.teapot
  gui_wait '.selected == "teapot"' "teapot selected"
  local x y
  x="$(gui_q '.object_px.teapot[0] | floor')"; y="$(gui_q '.object_px.teapot[1] | floor')"
  gui_move "$x" "$y"
  gui_frames 1
  gui_key t
  gui_wait '.tool == "Tile Paint"' "T picks the Tile Paint tool"
  gui_wait '.values["ddm.estimate_tiles"] != null and .values["ddm.estimate_tiles"] != ""' "an estimate is shown"
}

# Selects OBJECT, picks the Tile Paint tool with the mouse over it, and types FILE as its tile (Tile ▸ file, Tile file,
# Enter).
gui_tile_paint_file() {
  local object="$1" file="$2"
  gui_click_item "scene.object.$object"
  gui_wait ".selected == \"$object\"" "$object is selected"
  gui_move "$(gui_q ".object_px.$object[0] | floor")" "$(gui_q ".object_px.$object[1] | floor")"
  gui_frames 1
  gui_key t
  gui_wait '.tool == "Tile Paint"' "T picks the Tile Paint tool"
  gui_click_item ddm.tile
  gui_wait '.items["ddm.tile.file"] != null' "the Tile list opens"
  gui_click_item ddm.tile.file
  gui_wait '.items["ddm.tile_file"] != null' "Tile file appears"
  gui_click_item ddm.tile_file
  gui_wait '.typing' "one click on Tile file enters text editing"
  gui_type "$file"
  gui_key Return
  gui_wait '.typing | not' "Enter leaves Tile file"
}
