#!/usr/bin/env bash
# Tile layers riding on their objects in the real editor (core/scene/ddm_follow.h, the FOLLOW / FFD shader variants):
# tests/logs/ddm_follow.jsonl opened — thorns on a ring lattice, a DFFD split, an incision whose opening is keyed,
# hexagons on a placed rug. Every layer is drawn through its object's deformation; typing a frame moves the ring's
# thorns and opens the incision (the screenshots of frames 1 and 20 differ), and the editor stays alive.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/tests/logs/ddm_follow.jsonl"
gui_wait '(.objects | length) == 6' "the log opens with its six objects"
gui_wait '.tiles.layers == 4 and .tiles.following == 4 and .tiles.vertices > 100000' \
  "all four layers drawn through their objects' deformations"
gui_frames 2
gui_shot frame1
gui_click_item timeline.frame
gui_wait '.typing' "one click on the frame field enters text editing"
gui_type "20"
gui_key Return
gui_wait '.current_frame == 20 and (.typing | not)' "typing 20 + Enter sets frame 20"
gui_frames 3
gui_wait '.tiles.following == 4' "still drawn following at frame 20"
gui_shot frame20
cmp -s "$GUI_DIR/frame1.png" "$GUI_DIR/frame20.png" && gui_fail "frames 1 and 20 look the same: nothing moved"
gui_pass
