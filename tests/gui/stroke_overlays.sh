#!/usr/bin/env bash
# The stroke tools' live overlays, drawn by the renderer from what each tool's decorate() adds: mid-drag the Incision
# tool shows its stroke, the generator curve G(v), the cut lattice and the cut mesh in place of the sphere, and the
# release cuts once; the Tile Paint tool shows its stroke and the release paints once; nothing is left after.
source "$(dirname "$0")/gui_lib.sh"
echo '{"cmd":"scene.primitive","kind":"sphere","name":"s"}' > "$GUI_DIR/sphere.jsonl"
gui_start "$GUI_DIR/sphere.jsonl"
gui_wait '(.history.labels | length) >= 1' "the sphere is open"
gui_click_item scene.object.s
gui_wait '.selected == "s"' "sphere selected"
x="$(gui_q '.object_px.s[0] | floor')"
# Below the centre: the timing overlay covers the viewport's top left.
y=$(($(gui_q '.object_px.s[1] | floor') + 50))

# drag_across TOOL_CHECK: left-drag across the sphere's middle in small steps, running TOOL_CHECK before release.
drag_across() {
  local i
  gui_move $((x - 60)) "$y"
  gui_frames 1
  xdotool mousedown 1
  gui_frames 2
  for i in 1 2 3 4 5 6; do
    gui_move $((x - 60 + 20 * i)) $((y + 2 * i))
    gui_frames 1
  done
  "$1"
  xdotool mouseup 1
}

gui_key k
gui_wait '.tool == "Incision"' "K picks the Incision tool"
n="$(gui_q '.history.labels | length')"
incision_mid_drag() {
  gui_wait '.overlays.strokes == 1' "the stroke is shown while dragging"
  gui_wait '.overlays.curves == 1 and .overlays.meshes == 1 and .overlays.lattices == 1' \
    "G(v), the cut mesh and the cut lattice are shown while dragging" 30
  gui_key F12
  gui_frames 2
}
drag_across incision_mid_drag
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the incision" 60
gui_wait_logged '.cmd == "incision.draw"' "incision.draw logged"
gui_wait '.overlays.strokes == 0 and .overlays.curves == 0 and .overlays.meshes == 0' "no overlay after the release"

gui_key t
gui_wait '.tool == "Tile Paint"' "T picks the Tile Paint tool"
n="$(gui_q '.history.labels | length')"
paint_mid_drag() { gui_wait '.overlays.strokes == 1 and .overlays.curves == 0' "the paint stroke is shown while dragging"; }
drag_across paint_mid_drag
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the paint stroke" 90
gui_wait_logged '.cmd == "ddm.paint"' "ddm.paint logged"
gui_check '.overlays.strokes == 0' "no stroke after the release"
gui_pass
