#!/usr/bin/env bash
# CT/MRI volumes in the editor (seed ch. 7): Scene ▸ Load… of a real MRI (NIfTI) prepares it on a worker thread and
# adds it selected, with its Volume panel; a typed iso-level and a dragged one are one volume.iso each; silhouettes
# turned on are extracted for the current view on a worker thread and follow an orbit; Export ▸ SVG writes the view's
# silhouettes; a CT whose preprocessing is cancelled, a truncated .nii.gz and an empty folder chosen with "Load this
# folder" (a DICOM series is a folder) leave the scene unchanged and say so in the Log. Screenshots of the brain with
# its surface and silhouettes are kept in the test's folder.
source "$(dirname "$0")/gui_lib.sh"
mri="$GUI_ROOT/assets/data/KmeansTest_T1UCharRaw.nii.gz"
ct="$GUI_ROOT/assets/data/Cranium.inv3"
[ -f "$mri" ] || gui_fail "missing $mri (scripts/fetch_assets.sh fetches it)"
[ -f "$ct" ] || gui_fail "missing $ct (scripts/fetch_assets.sh fetches it)"
head -c 3000 "$mri" >"$GUI_WORK/truncated.nii.gz"
name=KmeansTest_T1UCharRaw
GUI_TIMEOUT=40
gui_start

load() {
  gui_click_item scene.load
  gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens, its path field has the keyboard"
  gui_type "$1"
  gui_key Return
}

# shot NAME: the editor's own screenshot (F12) once the volume is drawn at full resolution, as $GUI_DIR/NAME.png.
shot() {
  gui_wait '.volume_refining == false and (.volumes | map(.extracting) | any | not)' "the view settles before $1" 60
  gui_frames 2
  gui_screenshot "$1" || gui_fail "no screenshot for $1"
  gui_log "screenshot: $GUI_DIR/$1.png"
}

# 1. The MRI: prepared on a worker thread, then volume.load; selected, framed, its panel shown.
load "$mri"
gui_wait '.volumes | length == 1' "the MRI volume loads" 120
gui_check ".volumes[0].name == \"$name\"" "the volume is named after the file"
gui_check '.volumes[0].dims == [128, 128, 62]' "its grid is the file's"
gui_wait ".selected == \"$name\"" "the loaded volume is selected"
gui_wait '.items["volume.iso"] != null and .items["scene.object.'"$name"'"] != null' "the Volume panel and the Scene row show"
gui_wait '.volume_load == null and (.popups | length == 0)' "the progress window closes"
shot loaded

# 2. A typed iso-level: one volume.iso.
gui_click_item volume.iso
gui_wait '.typing' "a click on the iso field types a value"
gui_type 60
gui_key Return
gui_wait_logged '.cmd == "volume.iso" and .level == 60' "volume.iso at the typed level"
gui_wait '.volumes[0].iso == 60' "the volume's iso-level is 60"

# 3. A dragged iso-level: previewed while dragged, one volume.iso at release.
read -r x y <<<"$(gui_item_center volume.iso)"
gui_move "$x" "$y"
gui_frames 1
xdotool mousedown 1
gui_frames 2
for i in 1 2 3 4; do
  gui_move $((x + 15 * i)) "$y"
  gui_frames 1
done
gui_wait '.volumes[0].preview_iso != null and .volumes[0].preview_iso > 60' "the dragged level is previewed"
gui_check '.volumes[0].iso == 60' "the volume keeps its level while dragged"
xdotool mouseup 1
gui_wait_logged '.cmd == "volume.iso" and .level > 60' "a drag ends in one volume.iso"
[ "$(gui_session_count '.cmd == "volume.iso"')" = 2 ] || gui_fail "two volume.iso lines (typed, dragged)"
gui_wait '.volumes[0].iso > 60 and .volumes[0].preview_iso == null' "the dragged level applies"

# 4. Silhouettes on: extracted for the current view on a worker thread.
gui_click_item volume.silhouettes.enabled
gui_wait_logged '.cmd == "volume.silhouettes" and .enabled == true' "volume.silhouettes turns them on"
gui_wait '.volumes[0].silhouettes and .volumes[0].live_points > 100 and .volumes[0].live_current' \
  "live silhouettes for the current view" 90
shot silhouettes

# 5. An orbit (Alt + left drag): the silhouettes follow the new view.
eye_before="$(gui_q '.camera.eye | map(floor) | tostring')"
read -r vx vy <<<"$(gui_q '.viewport | "\(((.[0] + .[2]) / 2) | floor) \(((.[1] + .[3]) / 2 + 120) | floor)"')"
gui_drag "$vx" "$vy" $((vx + 120)) "$vy" alt
gui_wait "(.camera.eye | map(floor) | tostring) != \"$eye_before\"" "the view orbits"
gui_wait '.volumes[0].live_current and .volumes[0].live_points > 100' "the silhouettes follow the orbit" 90
shot orbited

# 5b. The Style combo: chromadepth colours the silhouettes by depth (red nearest, blue farthest; seed Figs. 7.8–7.9).
gui_click_item volume.silhouettes.style
gui_wait '.popups | length > 0' "the Style combo opens"
gui_click_item volume.silhouettes.style.chromadepth
gui_wait_logged '.cmd == "volume.silhouettes" and .style == "chromadepth"' "choosing chromadepth logs volume.silhouettes"
gui_wait '.popups | length == 0' "the Style combo closed"
gui_wait '.volumes[0].live_current and .volumes[0].live_points > 100' "the silhouettes are drawn in the new style" 90
shot chromadepth

# 5c. fans: fan glyphs whose opening and hue follow |∇D| (seed Fig. 7.11), then back to chromadepth for the export.
pick_style() {
  gui_click_item volume.silhouettes.style
  gui_wait '.popups | length > 0' "the Style combo opens"
  gui_click_item "volume.silhouettes.style.$1"
  gui_wait_logged ".cmd == \"volume.silhouettes\" and .style == \"$1\"" "choosing $1 logs volume.silhouettes"
  gui_wait '.popups | length == 0' "the Style combo closed"
  gui_wait '.volumes[0].live_current and .volumes[0].live_points > 100' "the silhouettes are drawn as $1" 90
}
pick_style fans
shot fans
pick_style chromadepth

# 5d. More levels (seed Figs. 7.4–7.6): Add level, type its value, pick its style: one volume.iso each, with every
# level; the new level's silhouettes are drawn live beside the surface's.
gui_scroll_into_view volume.levels.add panel.volume
gui_click_item volume.levels.add
gui_wait_logged '.cmd == "volume.iso" and (.levels | length) == 2' "Add level logs volume.iso with two levels"
gui_wait '.volumes[0].more_levels | length == 1' "the volume has a second level"
gui_scroll_into_view volume.levels.1 panel.volume
gui_click_item volume.levels.1
gui_wait '.typing' "one click on the level types a value"
gui_type "40"
gui_key Return
gui_wait_logged '.cmd == "volume.iso" and (.levels | length) == 2 and ((.levels[1] | if type == "object" then .level else . end) == 40)' \
  "the typed level is logged"
gui_click_item volume.levels.1.style
gui_wait '.popups | length > 0' "the level's style combo opens"
gui_click_item volume.levels.1.style.width
gui_wait_logged '.cmd == "volume.iso" and .levels[1].style == "width"' "the level's style is logged"
gui_wait '.volumes[0].more_levels[0].iso == 40 and .volumes[0].more_levels[0].style == "width"' "the level is 40, width"
gui_wait '.volumes[0].more_levels[0].live_points > 50' "the second level's silhouettes are drawn" 90
shot levels

# 6. Export ▸ SVG: the view's silhouettes as <path> elements, binned by depth in the chromadepth style.
gui_scroll_into_view volume.export.svg panel.volume
gui_click_item volume.export.svg
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Save dialog opens, its name field has the keyboard"
gui_check ".values[\"file.name\"] == \"${name}_silhouettes.svg\"" "the file name is proposed"
gui_type brain
gui_key Return
svg="$GUI_WORK/brain.svg"
for _ in $(seq 1 150); do [ -f "$svg" ] && break; sleep 0.2; done
[ -f "$svg" ] || gui_fail "the SVG was not written to $svg"
[ "$(grep -c '<path' "$svg")" -ge 1 ] || gui_fail "the SVG holds no <path element"
[ "$(grep -c 'data-depth=' "$svg")" -ge 2 ] || gui_fail "the chromadepth SVG holds no depth bins"
gui_wait_logged '.cmd == "volume.export" and .what == "silhouettes" and .path == "brain.svg"' \
  "volume.export logged with the file's name in the folder chosen in the dialog (a replay writes under its own --out)"
gui_wait_logged '.cmd == "volume.export" and .camera != null' "the export carries the view it was made for"

# 7. A CT whose preprocessing is cancelled: the progress window's Cancel; nothing added.
load "$ct"
gui_wait '.volume_load != null' "the CT starts loading" 30
gui_click_item volume.load.cancel
gui_wait '.volume_load == null' "the load stops" 60
gui_wait '.log | map(test("Loading Cranium.inv3 cancelled")) | any' "the Log says it was cancelled"
gui_check '.volumes | length == 1' "the scene is unchanged after the cancel"

# 8. A truncated .nii.gz: refused in the Log, the scene unchanged, the editor alive.
load "$GUI_WORK/truncated.nii.gz"
gui_wait '.log | map(test("cannot load truncated.nii.gz")) | any' "the truncated file is refused in the Log" 60
gui_wait '.volume_load == null' "the failed load is over"
gui_check '.volumes | length == 1' "the scene is unchanged after the refusal"

# 9. A folder (a DICOM series is one) chosen with the dialog's "Load this folder": an empty one is refused.
mkdir -p "$GUI_WORK/empty_series"
gui_click_item scene.load
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens again"
gui_type "$GUI_WORK/empty_series"
gui_key Return
gui_wait '.values["file.path"] | test("empty_series/$")' "Enter on a folder lists it"
gui_click_item file.folder
gui_wait '.log | map(test("cannot load empty_series")) | any' "the empty folder is refused in the Log" 60
gui_check '.volumes | length == 1' "the scene is unchanged after the folder"
gui_alive || gui_fail "the editor died"

[ "$(gui_session_count '.cmd == "volume.load"')" = 1 ] || gui_fail "one volume.load line in the session log"
[ "$(gui_session_count '.cmd == "volume.silhouettes"')" = 4 ] || gui_fail "four volume.silhouettes lines (on, chromadepth, fans, chromadepth)"
[ "$(gui_session_count '.cmd == "volume.export"')" = 1 ] || gui_fail "one volume.export line"
gui_pass
