#!/usr/bin/env bash
# Tile animation from the Tile Paint panel (seed §5.4.2): Fill the default scene's teapot, open Animation, choose no
# morph tile, type a turn of 0 → 360 degrees and a height of 1 → 2.5 over the frames, Animate: one ddm.animate in
# History and the session log with those rotate and w keys. Then Export ▸ Position map... / Normal map... (seed Figs.
# 5.3, 5.5): the Save dialog proposes a name, the typed one is written as a PNG holding the layer's maps, one ddm.export
# each in the session log; Esc in the dialog writes nothing; an existing name is replaced only on a second Save.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_teapot_tile_paint
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait "(.history.labels | length) == $((n + 1))" "Fill adds one history entry" 90

gui_scroll_into_view ddm.animation
gui_click_item ddm.animation
gui_wait '.items["ddm_anim.turn"] != null' "Animation opens with its Turn field"

# gui_type_pair NAME SIDE VALUE: clicks the left (0) or right (1) half of a two-number field and types VALUE.
gui_type_pair() {
  local x y
  gui_scroll_into_view "$1"
  gui_item_center "$1" >/dev/null
  x="$(gui_q ".items[\"$1\"] | (.[0] + (.[2] - .[0]) * (0.25 + 0.5 * $2)) | floor")"
  y="$(gui_q ".items[\"$1\"] | ((.[1] + .[3]) / 2) | floor")"
  gui_click "$x" "$y"
  gui_wait '.typing' "one click on $1 ($2) enters text editing"
  gui_type "$3"
  gui_key Return
  gui_wait '.typing | not' "$1 ($2) = $3 applied"
}
# No metamorphosis: the Morph to combo's last entry.
gui_scroll_into_view ddm_anim.morph
gui_click_item ddm_anim.morph
gui_wait '.items["ddm_anim.morph.none"] != null' "the Morph to list is open"
gui_click_item ddm_anim.morph.none
gui_wait '.values["ddm_anim.morph"] == ""' "no morph tile"
gui_type_pair ddm_anim.turn 1 360
gui_type_pair ddm_anim.w 1 2.5
gui_wait '.values["ddm_anim.blocked"] == ""' "Animate is enabled"

n="$(gui_q '.history.labels | length')"
gui_scroll_into_view ddm_anim.animate
gui_click_item ddm_anim.animate
gui_wait "(.history.labels | length) == $((n + 1))" "Animate adds one history entry" 60
gui_wait_logged '.cmd == "ddm.animate" and .rotate_keys == [[1,0],[96,360]] and .w_keys == [[1,1],[96,2.5]] and
  (has("morph_tile") and .morph_tile == "")' "ddm.animate logged with the typed turn and height keys"
gui_shot animated

# Export ▸ Position map...: the Save dialog, a typed name, the PNG in the dialog's folder (the editor's current one).
gui_scroll_into_view ddm.export.positions
gui_click_item ddm.export.positions
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Save dialog opens, its name field has the keyboard"
gui_check '.values["file.name"] | test("^teapot_.*_positions[.]png$")' "the file name is proposed"
gui_type teapot_p
gui_key Return
gui_wait '.popups | length == 0' "the dialog closes"
# check_map FILE KIND: a PNG of the layer's charts, opaque where sampled; normals decode to unit vectors.
check_map() {
  for _ in $(seq 1 150); do [ -f "$1" ] && break; sleep 0.2; done
  [ -f "$1" ] || gui_fail "the $2 map was not written to $1"
  "$GUI_PYTHON" - "$1" "$2" <<'PY' || gui_fail "the $2 map $1 is not a map of the layer"
import sys
import numpy as np
from PIL import Image
im = np.asarray(Image.open(sys.argv[1]).convert("RGBA")).astype(float) / 255.0
opaque = im[..., 3] > 0.99
assert im.shape[0] >= 64 and im.shape[1] >= 64, im.shape
assert opaque.mean() > 0.05, f"only {opaque.mean():.3f} of the texels are sampled"
rgb = im[..., :3][opaque]
assert rgb.std(axis=0).min() > 0.05, f"the colours hardly vary: {rgb.std(axis=0)}"
if sys.argv[2] == "normals":
    length = np.linalg.norm(rgb * 2.0 - 1.0, axis=1)
    assert abs(np.median(length) - 1.0) < 0.05, f"normals are not unit: median length {np.median(length):.3f}"
print(sys.argv[2], im.shape, f"sampled {opaque.mean():.3f}")
PY
}
check_map "$GUI_WORK/teapot_p.png" positions
gui_wait_logged '.cmd == "ddm.export" and .what == "positions" and .path == "teapot_p.png" and .object == "teapot"' \
  "ddm.export logged with the file's name in the folder chosen in the dialog"

# Normal map...: the same through its own button; Esc in the dialog writes nothing.
gui_click_item ddm.export.normals
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Save dialog opens for the normal map"
gui_check '.values["file.name"] | test("_normals[.]png$")' "the normal map's name is proposed"
gui_key Escape
gui_wait '.popups | length == 0' "Esc closes the dialog"
gui_frames 3
[ "$(gui_session_count '.cmd == "ddm.export"')" = 1 ] || gui_fail "Esc in the dialog logged a ddm.export"
gui_click_item ddm.export.normals
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Save dialog opens again"
gui_type teapot_n
gui_key Return
check_map "$GUI_WORK/teapot_n.png" normals
gui_wait_logged '.cmd == "ddm.export" and .what == "normals" and .path == "teapot_n.png"' "the normal map's ddm.export"
[ "$(gui_session_count '.cmd == "ddm.export"')" = 2 ] || gui_fail "two ddm.export lines in the session log"

# The same name again: the dialog says the file exists and stays open; a second Enter replaces it.
before="$(stat -c %Y.%s "$GUI_WORK/teapot_n.png")"
gui_click_item ddm.export.normals
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Save dialog opens a third time"
gui_type teapot_n
gui_key Return
gui_wait '.values["file.error"] == "teapot_n.png exists: Save again to replace it"' "the dialog asks before replacing"
gui_check '.popups | map(test("file_dialog")) | any' "the dialog stays open"
[ "$(stat -c %Y.%s "$GUI_WORK/teapot_n.png")" = "$before" ] || gui_fail "the file changed before the second Save"
[ "$(gui_session_count '.cmd == "ddm.export"')" = 2 ] || gui_fail "the first Save of an existing name logged a line"
gui_key Return
gui_wait '.popups | length == 0' "a second Enter confirms"
for _ in $(seq 1 100); do [ "$(gui_session_count '.cmd == "ddm.export"')" = 3 ] && break; sleep 0.2; done
[ "$(gui_session_count '.cmd == "ddm.export"')" = 3 ] || gui_fail "three ddm.export lines after the replace"
[ "$(stat -c %Y.%s "$GUI_WORK/teapot_n.png")" != "$before" ] || [ "$(gui_q '.log | map(test("saved the normals map of teapot/.* to .*teapot_n.png")) | length')" = 2 ] ||
  gui_fail "the second Save did not write the file again"
gui_pass
