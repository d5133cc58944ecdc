#!/usr/bin/env bash
# Articulated tiles (seed Fig. 5.13) through the editor: Tile Paint on the teapot, Tile ▸ file, Qt 3D's RiggedFigure
# (a skinned glTF) typed into Tile file, Up axis y (glTF figures stand on y), Play its animation ticked, Fill: one
# ddm.fill with tile_up "y" and tile_clip "*"; the layer is animated, so playing the Timeline moves the figures (two
# screenshots at different frames differ on the teapot).
source "$(dirname "$0")/gui_lib.sh"
figure="$GUI_ROOT/assets/data/qt3d/gltf/2.0/RiggedFigure/RiggedFigure.gltf"
[ -f "$figure" ] || gui_fail "missing $figure (scripts/fetch_assets.sh fetches Qt 3D's test data)"
cat >"$GUI_WORK/teapot.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"teapot","name":"teapot","color":[0.86,0.84,0.8]}
{"cmd":"camera.set","eye":[0,0.9,1.9],"target":[0,0.4,0],"up":[0,1,0],"fov_deg":36,"viewport":[1280,720]}
LOG
gui_start "$GUI_WORK/teapot.jsonl"
gui_wait '.objects == ["teapot"]' "the teapot is open"
gui_tile_paint_file teapot "$figure"
gui_click_item ddm.layer.tile_up
gui_wait '.items["ddm.layer.tile_up.y"] != null' "the Up axis list opens"
gui_click_item ddm.layer.tile_up.y
gui_frames 2
gui_click_item ddm.tile_clip
gui_frames 2
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait "(.history.labels | length) == $((n + 1))" "Fill adds one history entry" 120
gui_wait_logged '.cmd == "ddm.fill" and (.tile | endswith("RiggedFigure.gltf")) and .tile_up == "y" and .tile_clip == "*"' \
  "ddm.fill logged with the figure, up y and its animation"

# The figures walk: frames 1 and 13 of the Timeline differ where the tiles are.
gui_move 5 5
gui_frames 2
gui_shot frame_1
gui_click_item timeline.frame
gui_wait '.typing' "one click on the frame field enters text editing"
gui_type "13"
gui_key Return
gui_wait '.current_frame == 13' "the Timeline is at frame 13"
gui_move 5 5
gui_frames 3
gui_shot frame_13
# Pixels that differ in a 300 × 240 box around the teapot (the panels and tooltips left out).
changed="$("$GUI_PYTHON" - "$GUI_DIR/frame_1.png" "$GUI_DIR/frame_13.png" "$(gui_q '.object_px.teapot[0]')" \
  "$(gui_q '.object_px.teapot[1]')" <<'PY'
import sys
from PIL import Image, ImageChops
a, b = (Image.open(p).convert("RGB") for p in sys.argv[1:3])
x, y = float(sys.argv[3]), float(sys.argv[4])
box = (int(x - 150), int(y - 120), int(x + 150), int(y + 120))
diff = ImageChops.difference(a.crop(box), b.crop(box)).convert("L")
print(sum(1 for v in diff.getdata() if v > 24))
PY
)"
gui_log "$changed pixels around the teapot differ between frames 1 and 13"
[ "$changed" -ge 200 ] || gui_fail "the figures did not move between frames 1 and 13 ($changed pixels differ)"
gui_pass
