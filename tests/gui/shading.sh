#!/usr/bin/env bash
# View ▸ Shading in the real editor: a glTF cube whose faces carry a four-colour texture (red, green, blue, yellow
# quadrants, an embedded PNG) opens in Material shading — the scene has textures — and its pixels show the texture's
# colours; View ▸ Shading ▸ Solid draws it in one object colour (the texture's colours gone), and ▸ Material brings
# them back. Screenshots (F12) are read with a PNG decoder from Python's standard library.
source "$(dirname "$0")/gui_lib.sh"

python3 - "$GUI_WORK/cube.gltf" <<'EOF'
import base64, json, struct, sys, zlib
def png(w, h, px):  # px: rows of (r, g, b, a)
    raw = b"".join(b"\0" + bytes(c for p in row for c in p) for row in px)
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
Q = [(230, 20, 20, 255), (20, 200, 20, 255), (20, 40, 230, 255), (230, 210, 20, 255)]
img = png(8, 8, [[Q[(y >= 4) * 2 + (x >= 4)] for x in range(8)] for y in range(8)])
pos, nrm, uv, idx = [], [], [], []
for axis in range(3):
    for sign in (1, -1):
        n = [0, 0, 0]; n[axis] = sign
        u = [0, 0, 0]; u[(axis + 1) % 3] = 1
        v = [0, 0, 0]; v[(axis + 2) % 3] = 1
        base = len(pos)
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append([n[k] + a * u[k] + b * v[k] for k in range(3)])
            nrm.append(n)
            uv.append([(a + 1) / 2, (1 - b) / 2])
        quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
        idx += [base + i for i in quad]
blob = (b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *p) for p in nrm) +
        b"".join(struct.pack("<2f", *p) for p in uv) + b"".join(struct.pack("<H", i) for i in idx))
nv = len(pos)
gltf = {
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "cube"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                "material": 0}]}],
    "materials": [{"name": "quadrants", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                                 "metallicFactor": 0.0, "roughnessFactor": 0.6}}],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728}],
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(img).decode()}],
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": nv * 12},
                    {"buffer": 0, "byteOffset": nv * 12, "byteLength": nv * 12},
                    {"buffer": 0, "byteOffset": nv * 24, "byteLength": nv * 8},
                    {"buffer": 0, "byteOffset": nv * 32, "byteLength": len(idx) * 2}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3",
                   "min": [-1, -1, -1], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5126, "count": nv, "type": "VEC2"},
                  {"bufferView": 3, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
}
json.dump(gltf, open(sys.argv[1], "w"))
EOF
printf '{"cmd":"scene.load","path":"%s","name":"cube"}\n' "$GUI_WORK/cube.gltf" >"$GUI_WORK/cube.jsonl"

# colours PNG: how many of the texture's four colours cover at least 300 pixels (dominant channel by 60 levels) in
# the 180 × 180 px box around the cube's centre on screen (the probe's object_px; the panels and axis lines outside).
colours() {
  "$GUI_PYTHON" - "$1" "$(dirname "$0")" "$(gui_q '.object_px.cube[0]')" "$(gui_q '.object_px.cube[1]')" <<'EOF'
import sys
sys.path.insert(0, sys.argv[2])
from textured_pixels import read_rgb
rgb = read_rgb(sys.argv[1])
cx, cy = int(float(sys.argv[3])), int(float(sys.argv[4]))
box = rgb[max(0, cy - 90):cy + 90, max(0, cx - 90):cx + 90].reshape(-1, 3)
r, g, b = box[:, 0], box[:, 1], box[:, 2]
red = (r > g + 60) & (r > b + 60)
green = ~red & (g > r + 60) & (g > b + 60)
blue = ~red & ~green & (b > r + 60) & (b > g + 60)
yellow = ~red & ~green & ~blue & (r > b + 60) & (g > b + 60) & (abs(r - g) < 70)
counts = [int(m.sum()) for m in (red, green, blue, yellow)]
print(sum(c >= 300 for c in counts), counts, file=sys.stderr)
print(sum(c >= 300 for c in counts))
EOF
}

gui_start "$GUI_WORK/cube.jsonl"
gui_wait '.objects == ["cube"]' "the textured cube is open" 60
gui_frames 3
gui_shot material
n="$(colours "$GUI_DIR/material.png")"
[ "$n" -ge 3 ] || gui_fail "Material shading (the default for a textured scene) shows $n of the texture's 4 colours"

gui_click_item menu.View
gui_wait '.items["menu.Shading"] != null' "the View menu opens"
gui_click_item menu.Shading
gui_wait '.items["menu.Solid"] != null' "the Shading menu opens"
gui_click_item menu.Solid
gui_wait '.popups | length == 0' "the menu closes after picking Solid"
gui_frames 3
gui_shot solid
n="$(colours "$GUI_DIR/solid.png")"
[ "$n" -le 1 ] || gui_fail "Solid shading still shows $n of the texture's colours"

gui_click_item menu.View
gui_wait '.items["menu.Shading"] != null' "the View menu opens again"
gui_click_item menu.Shading
gui_wait '.items["menu.Material"] != null' "the Shading menu opens again"
gui_click_item menu.Material
gui_wait '.popups | length == 0' "the menu closes after picking Material"
gui_frames 3
gui_shot material_again
n="$(colours "$GUI_DIR/material_again.png")"
[ "$n" -ge 3 ] || gui_fail "View ▸ Shading ▸ Material shows $n of the texture's 4 colours"
gui_alive || gui_fail "the editor died"
gui_pass
