#!/usr/bin/env bash
# Scene ▸ Load… of PLY files as they come: a Blender-written one from assimp's test models (free text in its header,
# normals and uvs) loads whole; one with an element the mesh does not use between its vertices and faces loads its
# faces; a hostile one (a value glued to the next, `5-111`, once a 34 GB allocation) is refused in the Log with the
# element and value named, the scene unchanged and the editor alive.
source "$(dirname "$0")/gui_lib.sh"
real="$GUI_ROOT/assets/data/corpus/assimp/PLY/Wuson.ply"
[ -f "$real" ] || gui_fail "missing $real (scripts/fetch_assets.sh fetches the loader corpus)"
mkdir -p "$GUI_WORK/meshes"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement junk 2\nproperty double q\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n7\n-3\n3 0 1 2\n' \
  > "$GUI_WORK/meshes/extra.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty uchar flags\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n5-111 3 0 1 2\n' \
  > "$GUI_WORK/meshes/glued.ply"
gui_start
objects_before="$(gui_q '.objects | length')"

load() {
  gui_click_item scene.load
  gui_wait '(.popups | map(test("file_dialog")) | any) and .typing' "the Load dialog opens, its path field has the keyboard"
  gui_type "$1"
  gui_key Return
}

load "$real"
gui_wait ".objects | length == $objects_before + 1" "Wuson.ply loads" 60
gui_check '.objects | map(test("Wuson")) | any' "the object is named after the file"

load "$GUI_WORK/meshes/extra.ply"
gui_wait ".objects | length == $objects_before + 2" "a PLY with an extra element loads its faces" 30

load "$GUI_WORK/meshes/glued.ply"
gui_wait '.log | last | test("5-111. is not an unsigned integer")' "the hostile PLY is refused, naming the value" 30
gui_check ".objects | length == $objects_before + 2" "the scene is unchanged"
gui_alive || gui_fail "the editor died"
[ "$(gui_session_count '.cmd == "scene.load"')" = 2 ] || gui_fail "two scene.load lines in the session log"
gui_pass
