#!/usr/bin/env bash
# A textured inside in the real editor (seed Fig. 6.9's wood-textured caps): a ball split around a cylinder with capped
# openings, the cylinder hidden, seen from above into the hole the caps line. Select the ball, the Split (DFFD) tool,
# type the crate's planks PNG (tests/clients) into the Inside section's Texture field and 0.5 into Size, Apply → one
# object.inside in History and the session log as typed; in Material shading the caps, flat in the inside colour
# before, now show the planks (pixel to pixel, the hole's pixels vary several times more); No texture takes the image
# off, Ctrl+Z puts it back.
source "$(dirname "$0")/gui_lib.sh"
planks="$GUI_ROOT/tests/clients/data/crate/crate.png"
mkdir -p "$GUI_WORK/scenes"
cat >"$GUI_WORK/scenes/split_ball.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"sphere","name":"ball","color":[0.90,0.55,0.20]}
{"cmd":"scene.primitive","kind":"cylinder","name":"tool","scale":[0.3,1.6,0.3],"translate":[0.013,0,0.017],"color":[0.55,0.60,0.70]}
{"cmd":"dffd.split","object":"ball","obstacles":["tool"],"axis":"x","w_axis":"y","order":[3,3,3],"controls":[16,12,12],"kernel":"gaussian","kernel_width":0.7,"openings":"cap"}
{"cmd":"object.visibility","object":"tool","viewport":false,"render":false}
{"cmd":"object.inside","object":"ball","color":[0.95,0.9,0.85]}
{"cmd":"camera.set","eye":[1.2,2.6,0.6],"target":[0,0.2,0],"up":[0,1,0],"fov_deg":30,"viewport":[1280,720]}
LOG

gui_start "$GUI_WORK/scenes/split_ball.jsonl"
gui_wait '.objects == ["ball","tool"]' "the split ball is open"
# The caps in Material shading, nothing selected (a selected split object shows its lattice over it).
gui_view_shading Material
gui_move 5 5
gui_frames 3
gui_shot caps_flat

gui_click_item scene.object.ball
gui_wait '.selected == "ball"' "the ball is selected"
gui_click_item "tool.Split (DFFD)"
gui_wait '.tool == "Split (DFFD)"' "the Split (DFFD) tool is active"
gui_scroll_into_view inside.apply
gui_wait '.values["inside.current"] == ""' "the ball has no inside texture yet"
gui_click_item inside.texture
gui_wait '.typing' "one click on Texture enters text editing"
gui_type "$planks"
gui_wait ".values[\"inside.texture\"] == \"$planks\"" "the path is in the Texture field"
gui_key Return
gui_wait '.typing | not' "Enter leaves the Texture field"
gui_click_item inside.texture_size
gui_wait '.typing' "one click on Size enters text editing"
gui_type "0.5"
gui_key Return
gui_wait '.typing | not' "Enter applies the typed size"
n="$(gui_q '.history.applied')"
gui_click_item inside.apply
gui_wait ".history.applied == $((n + 1))" "Apply adds one history entry" 60
gui_wait_logged '.cmd == "object.inside" and .object == "ball" and (.texture | endswith("crate.png")) and
  ((.texture_size - 0.5) | fabs) < 1e-9' "object.inside logged with the typed texture and size"
gui_wait '.values["inside.current"] | endswith("crate.png")' "the ball's inside texture is the planks"

gui_move 940 500
gui_frames 1
gui_key q
gui_wait '.tool == "Select"' "Q: the Select tool"
gui_click 940 500
gui_wait '.selected == ""' "a click on the empty viewport deselects"
gui_move 5 5
gui_frames 3
gui_shot caps_textured
read -r changed flat textured < <("$GUI_PYTHON" - "$GUI_DIR/caps_flat.png" "$GUI_DIR/caps_textured.png" <<'PY'
# The pixels that changed, and the mean step between horizontal neighbours that both changed: the planks' grain
# against the flat colour's smooth shading.
import sys
import numpy as np
from PIL import Image
a, b = (np.asarray(Image.open(p).convert("RGB"), dtype=np.float64).sum(axis=2) for p in sys.argv[1:3])
changed = np.abs(a - b) > 30
pair = changed[:, 1:] & changed[:, :-1]
step = lambda im: float(np.abs(im[:, 1:] - im[:, :-1])[pair].mean()) if pair.any() else 0.0
print(int(changed.sum()), f"{step(a):.2f}", f"{step(b):.2f}")
PY
)
gui_log "$changed cap pixels changed; neighbour step flat $flat, textured $textured"
[ "$changed" -ge 3000 ] && "$GUI_PYTHON" -c "import sys; sys.exit(0 if $textured > 2 * max($flat, 1.0) else 1)" ||
  gui_fail "the caps do not show the planks texture ($changed changed, step $flat → $textured)"

gui_click_item scene.object.ball
gui_wait '.selected == "ball"' "the ball is selected again"
gui_click_item "tool.Split (DFFD)"
gui_wait '.tool == "Split (DFFD)"' "the Split (DFFD) tool again"
gui_scroll_into_view inside.no_texture
gui_click_item inside.no_texture
gui_wait ".history.applied == $((n + 2))" "No texture adds one history entry" 60
gui_wait_logged '.cmd == "object.inside" and .no_texture == true' "object.inside logged with no_texture"
gui_wait '.values["inside.current"] == ""' "the texture is off"
gui_key ctrl+z
gui_wait ".history.applied == $((n + 1))" "Ctrl+Z takes No texture back"
gui_wait '.values["inside.current"] | endswith("crate.png")' "the planks are back after Ctrl+Z"
gui_pass
