#!/usr/bin/env bash
# Tile Paint by tile size on the default scene's teapot: the panel starts from the teapot's body patches and a tile
# size, a typed tile size (at 3 fps) changes the tiles Fill would make as shown before Fill, and Fill makes exactly
# that many tiles, logged with the typed tile_size; above the vertex budget Fill asks first (Cancel, Fill anyway).
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_teapot_tile_paint
first="$(gui_q '.values["ddm.estimate_tiles"]')"
gui_log "estimate at the default tile size: $first tiles"

gui_click_item ddm.tile_size
gui_wait '.typing' "one click on Tile size enters text editing"
gui_type "0.2"
gui_key Return
gui_wait '(.typing | not) and .values["ddm.estimate_tiles"] != "'"$first"'"' "the typed size changes the estimate"
tiles="$(gui_q '.values["ddm.estimate_tiles"]')"
verts="$(gui_q '.values["ddm.estimate_vertices"]')"
gui_log "estimate at tile size 0.2: $tiles tiles, $verts tile vertices"
# The teapot body by size 0.2: 72 cells (ddm_counts_for_size of its one chart's world size), thorns of 626 vertices.
[ "$tiles" = 72 ] || gui_fail "estimate $tiles tiles at tile size 0.2 (expected 72)"
[ "$verts" = $((72 * 626)) ] || gui_fail "estimate $verts tile vertices (expected 72 thorns of 626)"

n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait "(.history.labels | length) == $((n + 1))" "Fill adds one history entry" 90
gui_wait_logged '.cmd == "ddm.fill" and .tile_size == 0.2 and .base == "teapot_body" and (has("counts") | not)' \
  "ddm.fill logged with the typed tile size on the teapot body"
gui_wait '.values["ddm.layer_tiles"] == "'"$tiles"'"' "Fill made the tiles the panel showed"

# Above the vertex budget (software GL here: 1 M) Fill asks first; Cancel builds nothing, Fill anyway builds.
gui_click_item ddm.tile_size
gui_wait '.typing' "one click on Tile size enters text editing again"
gui_type "0.04"
gui_key Return
gui_wait '(.typing | not) and (.values["ddm.estimate_vertices"] | tonumber) > 1000000' "a fill above the budget"
big="$(gui_q '.values["ddm.estimate_tiles"]')"
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait '.items["ddm.fill_cancel"] != null' "Fill asks before building $big tiles"
gui_click_item ddm.fill_cancel
gui_wait '.items["ddm.fill_cancel"] == null' "Cancel closes the question"
gui_frames 3
gui_check "(.history.labels | length) == $n" "Cancel built nothing"
gui_click_item ddm.fill
gui_wait '.items["ddm.fill_anyway"] != null' "Fill asks again"
gui_click_item ddm.fill_anyway
gui_wait "(.history.labels | length) == $((n + 1))" "Fill anyway adds one history entry" 110
gui_wait '.values["ddm.layer_tiles"] == "'"$big"'"' "Fill anyway made the tiles the panel showed"
gui_pass
