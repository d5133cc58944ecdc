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

# hues PNG: how many of 12 hue sectors hold at least 400 clearly coloured pixels (saturation ≥ 0.35, value ≥ 0.15).
hues() {
  python3 - "$1" <<'EOF'
import colorsys, struct, sys, zlib
data = open(sys.argv[1], "rb").read()
pos, idat = 8, b""
while pos < len(data):
    n, t = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if t == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and ctype in (2, 6), "8-bit RGB(A) PNG expected"
        bpp = 4 if ctype == 6 else 3
    elif t == b"IDAT":
        idat += body
    pos += 12 + n
raw, stride, prev, bins = zlib.decompress(idat), w * bpp, bytearray(w * bpp), [0] * 12
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    for x in range(0, stride, bpp):
        hh, s, v = colorsys.rgb_to_hsv(line[x] / 255, line[x + 1] / 255, line[x + 2] / 255)
        if s >= 0.35 and v >= 0.15: bins[min(11, int(hh * 12))] += 1
    prev = line
print(sum(n >= 400 for n in bins), bins, file=sys.stderr)
print(sum(n >= 400 for n in bins))
EOF
}
shot() { gui_screenshot "$1" || gui_fail "no screenshot written for $1"; }
view_menu_shading() {
  gui_click_item menu.View
  gui_wait '.items["menu.Shading"] != null' "the View menu opens"
  gui_click_item menu.Shading
  gui_wait ".items[\"menu.$1\"] != null" "the Shading menu opens"
  gui_click_item "menu.$1"
  gui_wait '.popups | length == 0' "the menu closes after picking $1"
  gui_frames 3
}

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
gui_frames 3
shot material
material_hues="$(hues "$GUI_DIR/material.png")"
view_menu_shading Solid
shot solid
solid_hues="$(hues "$GUI_DIR/solid.png")"
[ "$material_hues" -ge 3 ] && [ "$material_hues" -gt "$solid_hues" ] ||
  gui_fail "Material shading shows $material_hues hues, Solid $solid_hues: the rack's textures are not drawn"
view_menu_shading Material

# Place the rack along a stroke sketched over the ground, left to right below it.
gui_click_item "scene.object.$rack"
gui_wait ".selected == \"$rack\"" "the rack is selected"
gui_key w
gui_wait '.tool == "Sketch placement"' "W picks the Sketch tool"
vx0="$(gui_q '.viewport[0] | floor')"; vy0="$(gui_q '.viewport[1] | floor')"
vx1="$(gui_q '.viewport[2] | floor')"; vy1="$(gui_q '.viewport[3] | floor')"
y=$((vy0 + (vy1 - vy0) * 85 / 100))
n="$(gui_q '.history.labels | length')"
gui_drag $((vx0 + (vx1 - vx0) / 4)) "$y" $((vx0 + (vx1 - vx0) * 3 / 4)) $((y - 10))
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the placement" 180
gui_wait_logged ".cmd == \"place.sketch\" and .object == \"$rack\"" "place.sketch of the rack in the session log"
place_label="$(gui_q '.history.labels | last')"
gui_frames 3
shot placed
placed_hues="$(hues "$GUI_DIR/placed.png")"
[ "$placed_hues" -ge 3 ] || gui_fail "the placed rack shows $placed_hues hues: its textures did not follow the FFD"

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
gui_frames 3
shot reopened
reopened_hues="$(hues "$GUI_DIR/reopened.png")"
[ "$reopened_hues" -ge 3 ] || gui_fail "after Open the rack shows $reopened_hues hues: its textures are lost"
gui_alive || gui_fail "the editor died"

# The saved scene's export, read by the real clients.
for client in validator blender; do
  python3 "$GUI_ROOT/tests/clients/check_exports.py" --trispline "$TRISPLINE" --log "$GUI_WORK/scenes/textured.jsonl" \
    --out "$GUI_WORK/export_$client" --client "$client" --min-materials 3 --min-images 3 \
    --node-path "$(dirname "$TRISPLINE")/../test-tools/node_modules" >"$GUI_DIR/clients_$client.log" 2>&1 ||
    { cat "$GUI_DIR/clients_$client.log"; gui_fail "the saved scene's export fails the $client"; }
done
gui_pass
