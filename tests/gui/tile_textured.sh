#!/usr/bin/env bash
# Texture-mapped tiles (seed Fig. 5.12) through the editor: Tile Paint on a blue ball, Tile ▸ file, the crate of
# tests/clients typed into Tile file (an OBJ + MTL with PNG planks and a leaf cut-out), Fill by tile size; the scene
# switches to Material shading by itself (a textured scene), where the tiles show the crate's textures — the ball's
# blue of Solid replaced by the planks' colours (textured_pixels.py) — and ddm.fill is logged with the tile file;
# Ctrl+S and the headless replay of that log export the tile layer with the crate's materials and images.
source "$(dirname "$0")/gui_lib.sh"
crate="$GUI_ROOT/tests/clients/data/crate/crate.obj"
mkdir -p "$GUI_WORK/scenes"
cat >"$GUI_WORK/scenes/ball.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"sphere","name":"ball","color":[0.15,0.3,0.95]}
{"cmd":"camera.set","eye":[0,1.2,3.2],"target":[0,0,0],"up":[0,1,0],"fov_deg":38,"viewport":[1280,720]}
LOG

gui_start "$GUI_WORK/scenes/ball.jsonl"
gui_wait '.objects == ["ball"]' "the ball is open"
gui_tile_paint_file ball "$crate"
gui_click_item ddm.tile_size
gui_wait '.typing' "one click on Tile size enters text editing"
gui_type "0.35"
gui_key Return
gui_wait '(.typing | not) and .values["ddm.estimate_error"] == "" and (.values["ddm.estimate_tiles"] | tonumber) > 20' \
  "the estimate counts crate tiles" 60
n="$(gui_q '.history.labels | length')"
gui_click_item ddm.fill
gui_wait "(.history.labels | length) == $((n + 1))" "Fill adds one history entry" 120
# The typed 0.35 is logged as 0.35000000000000003 (one ulp; the Tile size field's text → double path), hence the
# tolerance.
gui_wait_logged '.cmd == "ddm.fill" and (.tile | endswith("crate.obj")) and ((.tile_size - 0.35) | fabs) < 1e-12' \
  "ddm.fill logged with the crate tile and the typed size"

# Material shading (automatic: the scene now has textures) against Solid, on the ball's pixels.
gui_move 5 5
gui_frames 3
gui_shot tiles_material
gui_view_shading Solid
gui_shot tiles_solid
cx="$(gui_q '.object_px.ball[0]')"; cy="$(gui_q '.object_px.ball[1]')"
read -r -a r < <("$GUI_PYTHON" "$(dirname "$0")/textured_pixels.py" "$GUI_DIR/tiles_material.png" \
  "$GUI_DIR/tiles_solid.png" "$cx" "$cy")
gui_log "${r[0]} pixels differ; Solid's ball blue ${r[1]} % of them, Material ${r[2]} %"
[ "${r[0]}" -ge 8000 ] && [ "${r[1]}" -ge 50 ] && [ "${r[2]}" -le 5 ] ||
  gui_fail "the tiles are not drawn with the crate's textures in Material shading (${r[*]})"

# The saved log replays headless into a scene.glb whose tile layer carries the crate's materials and images.
gui_key ctrl+s
gui_wait '.log | last | test("[Ss]aved")' "Ctrl+S saves the scene"
"$TRISPLINE" replay "$GUI_WORK/scenes/ball.jsonl" --out "$GUI_WORK/replayed" --no-render > "$GUI_DIR/replay.txt" 2>&1 ||
  gui_fail "the saved log does not replay: $(cat "$GUI_DIR/replay.txt")"
python3 - "$GUI_WORK/replayed/scene.glb" <<'PY' || gui_fail "scene.glb's tile layer has no crate materials"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
doc = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
mesh = next(m for m in doc["meshes"] if "/" in m["name"])
used = {doc["materials"][p["material"]]["name"] for p in mesh["primitives"]}
textured = [p for p in mesh["primitives"] if "TEXCOORD_0" in p["attributes"]]
print(mesh["name"], sorted(used), len(doc.get("images", [])), "images")
sys.exit(0 if {"wood", "leaf"} <= used and textured and len(doc.get("images", [])) >= 2 else 1)
PY
gui_pass
