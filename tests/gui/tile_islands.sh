#!/usr/bin/env bash
# Tile Paint on a mesh without texture coordinates (the Stanford bunny as loaded: automatic UVs) counts the vertex budget
# on the tiles its UV islands keep: a typed tile size whose layout cells would make over 10 M tile vertices shows
# "up to" that many, no error, and Fill (asked first above the software-GL budget) lays the kept tiles, fewer than
# the cells, within the budget, as one logged ddm.fill.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/tests/logs/bunny_alone.jsonl"
gui_wait '(.history.labels | length) >= 2' "the log is open"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"
x="$(gui_q '.object_px.bunny[0] | floor')"; y="$(gui_q '.object_px.bunny[1] | floor')"
gui_move "$x" "$y"
gui_frames 1
gui_key t
gui_wait '.tool == "Tile Paint"' "T picks the Tile Paint tool"
gui_wait '.values["ddm.estimate_tiles"] != null and .values["ddm.estimate_tiles"] != ""' "an estimate is shown"

gui_click_item ddm.tile_size
gui_wait '.typing' "one click on Tile size enters text editing"
gui_type "0.04"
gui_key Return
gui_wait '(.typing | not) and .values["ddm.estimate_error"] == "" and (.values["ddm.estimate_vertices"] | tonumber) > 10000000' \
  "cells for over 10 M tile vertices before pruning, and no error" 60
cells="$(gui_q '.values["ddm.estimate_tiles"]')"
gui_log "estimate at tile size 0.04: up to $cells tiles, $(gui_q '.values["ddm.estimate_vertices"]') tile vertices"
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait '.items["ddm.fill_anyway"] != null' "above the software-GL budget Fill asks first"
gui_click_item ddm.fill_anyway
gui_wait "(.history.labels | length) == $((n + 1))" "Fill adds one history entry" 110
gui_wait_logged '.cmd == "ddm.fill" and .object == "bunny" and .tile_size == 0.04 and .base == "auto_uv"' \
  "ddm.fill logged with the typed tile size on the automatic UVs"
gui_wait '.values["ddm.layer_tiles"] != null and .values["ddm.layer_tiles"] != ""' "the layer's tiles are shown"
kept="$(gui_q '.values["ddm.layer_tiles"]')"
gui_log "Fill kept $kept of $cells cells"
[ "$kept" -gt 0 ] && [ "$kept" -lt "$cells" ] || gui_fail "kept $kept tiles of $cells cells (expected some pruned)"
[ $((kept * 626)) -le 10000000 ] || gui_fail "$kept thorns exceed the 10 M tile-vertex budget"
gui_shot filled
gui_pass
