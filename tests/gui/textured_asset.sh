#!/usr/bin/env bash
# A real textured asset through the editor as an artist uses it: Scene ▸ Load… of Qt 3D's wine rack (Collada, JPEG
# textures; fetched by scripts/fetch_assets.sh) over a ground plane; Material shading (the default for a textured
# scene) shows the textures — many colours where Solid shows the object colour; the rack is placed along a stroke
# sketched over the ground and keeps its textures; a ball is hidden with the eye icon; Ctrl+S, File ▸ New and File ▸
# Open give back the placement, the hidden ball and the textures; the saved log's export passes the Khronos glTF
# validator and Blender's glTF importer (tests/clients/check_exports.py) with the rack's materials and images.
source "$(dirname "$0")/gui_lib.sh"
wine="$GUI_ROOT/assets/data/qt3d/gltf/wine/wine.dae"
[ -f "$wine" ] || gui_fail "missing $wine (scripts/fetch_assets.sh fetches Qt 3D's example assets)"

mkdir -p "$GUI_WORK/scenes"
cat >"$GUI_WORK/scenes/textured.jsonl" <<'LOG'
{"cmd":"scene.primitive","kind":"plane","name":"ground","scale":400,"translate":[80,-8,0]}
{"cmd":"scene.primitive","kind":"sphere","name":"ball","scale":10,"translate":[80,60,0]}
LOG


gui_start "$GUI_WORK/scenes/textured.jsonl"
gui_wait '.objects == ["ground", "ball"]' "the ground and the ball are open"

# Scene ▸ Load… the Collada file; its 3 line elements are left out with the dialog's option.
gui_click_item scene.load
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens, its path field has the keyboard"
gui_click_item file.option
gui_wait '.values["file.option"] == "on"' "Leave out points and lines is on"
gui_click_item file.path
gui_wait '.typing and .active == "file.path"' "the path field has the keyboard"
gui_type "$wine"
gui_key Return
gui_wait '.objects | length == 3' "the wine rack loads" 120
rack="$(gui_q '.objects[2]')"
gui_wait_logged ".cmd == \"scene.load\" and .loose == \"ignore\"" "scene.load of the rack in the session log"
# check_textured NAME: Material and Solid screenshots of the current view; the rack drawn with its textures
# (textured_pixels.py: the object colour of Solid replaced by the textures' colours).
check_textured() {
  local cx cy r
  gui_frames 3
  gui_shot "$1_material"
  gui_view_shading Solid
  gui_shot "$1_solid"
  gui_view_shading Material
  cx="$(gui_q ".object_px[\"$rack\"][0]")"; cy="$(gui_q ".object_px[\"$rack\"][1]")"
  read -r -a r < <("$GUI_PYTHON" "$(dirname "$0")/textured_pixels.py" "$GUI_DIR/$1_material.png" "$GUI_DIR/$1_solid.png" \
    "$cx" "$cy")
  gui_log "$1: ${r[0]} pixels differ; Solid's object colour ${r[1]} % of them, Material ${r[2]} %"
  [ "${r[0]}" -ge 8000 ] && [ "${r[1]}" -ge 50 ] && [ "${r[2]}" -le 5 ] ||
    gui_fail "$1: the rack is not drawn with its textures in Material shading (${r[*]})"
}
check_textured loaded

# Place the rack along a stroke sketched over the ground, left to right below it.
gui_click_item "scene.object.$rack"
gui_wait ".selected == \"$rack\"" "the rack is selected"
vx0="$(gui_q '.viewport[0] | floor')"; vy0="$(gui_q '.viewport[1] | floor')"
vx1="$(gui_q '.viewport[2] | floor')"; vy1="$(gui_q '.viewport[3] | floor')"
gui_move $(((vx0 + vx1) / 2)) $(((vy0 + vy1) / 2))  # shortcuts go to the viewport under the mouse
gui_frames 1
gui_key w
gui_wait '.tool == "Sketch placement"' "W picks the Sketch tool"
# The rack is 168 × 46 × 60 world units: a half-width and height of its own size, typed into the panel's fields.
for field in width:30 height:45; do
  gui_click_item "place.sketch.${field%%:*}"
  gui_wait '.typing' "one click on ${field%%:*} enters text editing"
  gui_type "${field#*:}"
  gui_key Return
  gui_wait '.typing | not' "Enter leaves the ${field%%:*} field"
done
gui_move $(((vx0 + vx1) / 2)) $(((vy0 + vy1) / 2))
gui_frames 1
y=$((vy0 + (vy1 - vy0) * 85 / 100))
n="$(gui_q '.history.labels | length')"
gui_drag $((vx0 + (vx1 - vx0) / 4)) "$y" $((vx0 + (vx1 - vx0) * 3 / 4)) $((y - 10))
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the placement" 180
gui_wait_logged ".cmd == \"place.sketch\" and .object == \"$rack\" and .width == 30 and .height == 45" \
  "place.sketch of the rack with the typed sizes in the session log"
place_label="$(gui_q '.history.labels | last')"
check_textured placed

# Hide the ball with the eye icon, save, open again.
gui_click_item scene.eye.ball
gui_wait '.hidden == ["ball"]' "the eye hides the ball"
gui_key ctrl+s
gui_wait '.log | last | test("[Ss]aved")' "Ctrl+S saves the scene"
gui_key ctrl+n
gui_wait '.objects == []' "File ▸ New empties the scene"
gui_key ctrl+o
gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Open dialog opens, its path field has the keyboard"
gui_type "$GUI_WORK/scenes/textured.jsonl"
gui_key Return
gui_wait ".objects == [\"ground\", \"ball\", \"$rack\"] and .hidden == [\"ball\"]" \
  "after Open the rack is back and the ball still hidden" 180
gui_check ".history.labels | index(\"$place_label\") != null" "the placement ($place_label) is back in the History"
check_textured reopened
gui_alive || gui_fail "the editor died"

# The saved scene's export, read by the real clients.
for client in validator blender; do
  python3 "$GUI_ROOT/tests/clients/check_exports.py" --trispline "$TRISPLINE" --log "$GUI_WORK/scenes/textured.jsonl" \
    --out "$GUI_WORK/export_$client" --client "$client" --min-materials 3 --min-images 3 \
    --node-path "$(dirname "$TRISPLINE")/../test-tools/node_modules" >"$GUI_DIR/clients_$client.log" 2>&1 ||
    { cat "$GUI_DIR/clients_$client.log"; gui_fail "the saved scene's export fails the $client"; }
done
gui_pass
