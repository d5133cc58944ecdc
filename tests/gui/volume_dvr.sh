#!/usr/bin/env bash
# Direct volume rendering in the editor (seed §7.4, Fig. 7.7): the real T1 MRI loaded through Scene ▸ Load…, its
# Volume panel's Render combo switched to "dvr" (one volume.render line with the volume's default transfer function,
# a ramp from the iso-level, since an MR volume is not in HU); a transfer point's value typed, a point added and one
# removed, a preset chosen, the step typed — one volume.render line each, carrying the whole function — and Ctrl+Z
# taking the last change back. Screenshots of the volume as drawn are kept in the test's folder.
source "$(dirname "$0")/gui_lib.sh"
mri="$GUI_ROOT/assets/data/KmeansTest_T1UCharRaw.nii.gz"
[ -f "$mri" ] || gui_fail "missing $mri (scripts/fetch_assets.sh fetches it)"
GUI_TIMEOUT=40
gui_start

# shot NAME: the editor's own screenshot (F12) once the volume is drawn at full resolution.
shot() {
  gui_wait '.volume_refining == false' "the view settles before $1" 90
  gui_frames 2
  gui_screenshot "$1" || gui_fail "no screenshot for $1"
  gui_log "screenshot: $GUI_DIR/$1.png"
}

gui_click_item scene.load
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens, its path field has the keyboard"
gui_type "$mri"
gui_key Return
gui_wait '.volumes | length == 1' "the MRI volume loads" 120
gui_wait '.volume_load == null and (.popups | length == 0)' "the progress window closes"
gui_wait '.items["volume.render.mode"] != null' "the Volume panel shows its Render section"
gui_check '.volumes[0].render == "iso"' "a loaded volume shows its iso-surface"
shot iso

# 1. Render ▸ dvr: one volume.render line with the default transfer function (3 points).
gui_scroll_into_view volume.render.mode panel.volume
gui_click_item volume.render.mode
gui_wait '.popups | length > 0' "the Render combo opens"
gui_click_item volume.render.mode.dvr
gui_wait_logged '.cmd == "volume.render" and .mode == "dvr" and (.transfer | length) == 3' \
  "choosing dvr logs volume.render with the volume's default transfer function"
gui_wait '.volumes[0].render == "dvr" and (.volumes[0].transfer_values | length) == 3' "the volume is drawn by dvr"
shot dvr

# 2. Type a point's value: one line, the function's second point at the typed value.
gui_scroll_into_view volume.transfer.1 panel.volume
gui_click_item volume.transfer.1
gui_wait '.typing' "one click on the point's value types a value"
gui_type "120"
gui_key Return
gui_wait_logged '.cmd == "volume.render" and .transfer[1][0] == 120' "the typed value is logged"
gui_wait '.volumes[0].transfer_values[1] == 120' "the volume's transfer function has the typed point"

# 3. Add point (halfway between the last two), then remove the first: 4, then 3 points.
gui_scroll_into_view volume.transfer.add panel.volume
gui_click_item volume.transfer.add
gui_wait_logged '.cmd == "volume.render" and (.transfer | length) == 4' "Add point logs four points"
gui_wait '(.volumes[0].transfer_values | length) == 4' "the function has four points"
gui_scroll_into_view volume.transfer.0.remove panel.volume
gui_click_item volume.transfer.0.remove
gui_wait_logged '.cmd == "volume.render" and (.transfer | length) == 3 and .transfer[0][0] == 120' \
  "removing the first point logs three points, the typed one first"
shot edited

# 4. The step, typed.
gui_scroll_into_view volume.render.step panel.volume
gui_click_item volume.render.step
gui_wait '.typing' "one click on the step types a value"
gui_type "0.25"
gui_key Return
gui_wait_logged '.cmd == "volume.render" and .step == 0.25' "the typed step is logged"

# 5. Ctrl+Z: the step back to 0.5 (the line without it), the points kept.
n=$(gui_session_count '.cmd == "volume.render"')
gui_key ctrl+z
gui_wait '.volumes[0].render == "dvr" and (.volumes[0].transfer_values | length) == 3' "after undo still dvr, three points"
gui_wait '.history.applied < (.history.labels | length)' "the step's line is undone"

# 6. Back to the iso-surface.
gui_scroll_into_view volume.render.mode panel.volume
gui_click_item volume.render.mode
gui_wait '.popups | length > 0' "the Render combo opens again"
gui_click_item volume.render.mode.iso
gui_wait_logged '.cmd == "volume.render" and .mode == "iso"' "choosing iso logs volume.render"
gui_wait '.volumes[0].render == "iso"' "the iso-surface is drawn again"
gui_alive || gui_fail "the editor died"
[ "$(gui_session_count '.cmd == "volume.render"')" -ge 6 ] || gui_fail "six volume.render lines in the session log"
gui_pass
