#!/usr/bin/env bash
# Opening a log never writes files (docs/decisions.md): the editor opens a log that exports a torus volume's
# silhouettes (volume.export) and records frames (anim.record); neither the SVG nor the frames are written, the History
# says "not written again", and its Run again buttons (real clicks) write the SVG and record the frame, but refuse a
# recording whose folder is outside the scene's (a shared log must not write there). Then the
# Record dialog (File ▸ Record animation...) offers the scene camera (the log has a camera.set) and, clicked, the
# current view: the anim.record line carries that view's camera and the frame is recorded.
source "$(dirname "$0")/gui_lib.sh"
log="$GUI_WORK/torus_scene.jsonl"
cat >"$log" <<'LOG'
{"cmd":"volume.load","analytic":"torus","name":"torus","iso":0}
{"cmd":"volume.silhouettes","object":"torus","style":"plain","hidden":"remove"}
{"cmd":"camera.set","eye":[0,-110,70],"target":[0,0,0],"up":[0,0,1],"fov_deg":40,"viewport":[160,120]}
{"cmd":"volume.export","object":"torus","what":"silhouettes","path":"torus.svg"}
{"cmd":"anim.timeline","fps":24,"start":1,"end":1}
{"cmd":"anim.record","out":"opened_frames","format":"png","frames":[1,1],"glb":false,"mp4":false,"width":48,"height":32}
{"cmd":"anim.record","out":"../outside_frames","format":"png","frames":[1,1],"glb":false,"mp4":false,"width":48,"height":32}
LOG
svg="$GUI_WORK/torus.svg"
GUI_TIMEOUT=40
gui_start "$log"

# 1. Opened: five history steps, the export not written, the recording a row after them, not recorded.
gui_wait '(.history.labels | length) == 5 and .history.applied == 5' "the log opens with five steps"
gui_check '.history.not_written == [false, false, false, true, false]' "the export is marked not written again"
gui_check '(.history.outputs | length) == 2 and .history.outputs[0].not_written and .history.outputs[0].after == 5' \
  "the recordings are shown after the last step, not recorded"
gui_frames 3
[ -e "$svg" ] && gui_fail "Open wrote $svg"
[ -e "$GUI_WORK/opened_frames" ] && gui_fail "Open recorded into opened_frames"

# 2. Undo and redo through the History (clicks on its rows): still nothing written.
gui_click_item history.row.2
gui_wait '.history.applied == 2' "a click on row 2 undoes back to it"
gui_click_item history.row.5
gui_wait '.history.applied == 5' "a click on row 5 redoes up to it"
gui_frames 2
[ -e "$svg" ] && gui_fail "a History jump wrote $svg"

# 3. Run again on the export: the SVG is written, no new step.
gui_click_item history.run_again.4
for _ in $(seq 1 100); do [ -f "$svg" ] && break; sleep 0.2; done
[ -f "$svg" ] || gui_fail "Run again did not write $svg"
grep -q '<path' "$svg" || gui_fail "the SVG holds no <path element"
gui_wait '.history.not_written[3] == false' "the export is no longer marked"
gui_check '(.history.labels | length) == 5 and .history.applied == 5' "Run again added no history step"
gui_wait '.log | map(test("wrote .*torus.svg")) | any' "the Log says what was written"

# 4. Run again on the recording: its frame is recorded into the line's folder.
gui_click_item history.output_run_again.0
frame="$GUI_WORK/opened_frames/frame_0001.png"
for _ in $(seq 1 150); do [ -f "$frame" ] && break; sleep 0.2; done
[ -f "$frame" ] || gui_fail "Run again did not record $frame"
gui_wait '.history.outputs[0].not_written == false' "the recording is no longer marked"
gui_wait '.popups | length == 0' "the recording's progress closes" 60

# 4b. A shared log's recording outside the scene's folder: Run again refuses it and records nothing.
gui_click_item history.output_run_again.1
gui_wait '.log | map(test("Run again refused: the log records into .*outside_frames")) | any' \
  "Run again refuses a folder outside the scene's"
gui_frames 3
[ -e "$GUI_WORK/../outside_frames" ] && gui_fail "Run again recorded outside the scene's folder"
gui_check '.history.outputs[1].not_written' "the refused recording stays marked"

# 5. The Record dialog says which camera it records and lets the artist choose the current view.
n="$(gui_session_count '.cmd == "anim.record"')"
gui_click_item menu.File
gui_click_item "menu.Record animation..."
gui_wait '.popups | map(test("Record animation")) | any' "the Record dialog opens"
gui_wait '.values["record.camera"] == "scene"' "the scene camera (the log's camera.set) is preset"
gui_click_item record.camera.view
gui_wait '.values["record.camera"] == "view"' "a click chooses the current view"
gui_click_item record.ok
gui_wait_logged '.cmd == "anim.record" and .camera != null and (.camera.eye | length) == 3' \
  "anim.record carries the current view's camera"
[ "$(gui_session_count '.cmd == "anim.record"')" -gt "$n" ] || gui_fail "no new anim.record line"
out="$(jq -r 'select(.cmd == "anim.record" and .camera != null) | .out' "$GUI_STATE/session.jsonl" | tail -1)"
for _ in $(seq 1 300); do [ -f "$out/frame_0001.png" ] && break; sleep 0.2; done
[ -f "$out/frame_0001.png" ] || gui_fail "the chosen view was not recorded into $out"
gui_wait '.popups | length == 0' "the recording ends" 90
gui_pass
