#!/usr/bin/env bash
# Tile animation from the Tile Paint panel (seed §5.4.2): Fill the default scene's teapot, open Animation, choose no
# morph tile, type a turn of 0 → 360 degrees and a height of 1 → 2.5 over the frames, Animate: one ddm.animate in
# History and the session log with those rotate and w keys.
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
gui_pass
