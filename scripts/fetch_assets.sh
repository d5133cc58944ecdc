#!/usr/bin/env bash
# Fetches the real input meshes and volumes from Debian data packages into assets/data/ (git-ignored; never commit them):
#   glmark2-data → bunny.obj (Stanford bunny, 34,835 vertices); gem-doc → venus.obj (Venus bust, 711 vertices);
#   assimp-testmodels (20 MB, downloaded once for both) → glTF animation clips for core::MeshClip:
#     AnimatedMorphCube/AnimatedMorphCube.gltf + .bin (Khronos sample, morph-target weights, 24 vertices) and
#     simple_skin/simple_skin.gltf (glTF tutorial skin: two joints, 10 vertices, buffers embedded);
#   libcgal-demo (23 MB) → nefertiti.off (CGAL's data/meshes/nefertiti.off, a face mask: 299 vertices, 562 triangles,
#     one open boundary, looking along +z; CC0 per CGAL's LICENSE), from the data.tar.gz the package ships;
#   fonts-symbola (1.3 MB) → fonts/Symbola_hint.ttf (George Douros' Symbola, free for any use): its U+1F5E3 SPEAKING
#     HEAD IN SILHOUETTE is the face profile molded into a part in assets/scenes/seed/face_mould.jsonl (seed Fig. 6.2).
# Real volumes for core/volume's loaders (tests/core/volume/test_volume_io.cpp):
#   invesalius-examples (19 MB) → Cranium.inv3 (InVesalius project of a CT skull: 256×256×108 int16 HU samples,
#     0.957×0.957×1.5 mm); insighttoolkit5-examples (2 MB) → KmeansTest_T1UCharRaw.nii.gz (ITK's T1 MRI brain,
#     128×128×62 uint8 samples, 2×2×3 mm).
# A corpus of real mesh files the project does not ship, for the loader test (tests/core/mesh/test_mesh_corpus.cpp):
#   corpus/cgal/      CGAL's data/meshes (libcgal-demo): ~150 OFF/PLY/OBJ/STL meshes, polygonal, coloured, broken;
#   corpus/assimp/    assimp's own test models (assimp-testmodels) for OBJ, PLY, OFF, STL, invalid files included;
#   corpus/geomview/  Geomview's sample OFF files (geomview): per-face colours, COFF, comments, 4OFF.
# Textured models for materials (tests/core/mesh/test_qt3d_assets.cpp), Qt 3D's example assets (qt3d5-examples, 266 MB
# download, 67 MB kept) → qt3d/: gltf/wine/ (wine.dae: Collada, 3 JPEG textures; wine.gltf is glTF 1.0),
#   gltf/2.0/RiggedFigure/ and RiggedSimple/ (glTF 2.0 skins), obj/ (toyplane.obj, ball.obj, trefoil.obj, …),
#   test_scene.dae (Collada, two materials), textures/ (PBR PNG sets up to 4 K), cubemaps/, envmaps/.
# Uses `apt-get download` + `dpkg-deb -x`: nothing is installed. Idempotent: does nothing when the files exist.
# Usage: scripts/fetch_assets.sh [--editor | --check]
#   --editor  only what the default scene needs (bunny.obj, 1 MB): scripts/start.sh; the rest comes with the tests
#   --check   says which assets are missing, fetching nothing; exit 1 if any
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="$root/assets/data"
mode="${1:-all}"
if [ "$mode" = --check ]; then
  missing=()
  for f in bunny.obj venus.obj AnimatedMorphCube/AnimatedMorphCube.gltf simple_skin/simple_skin.gltf Cranium.inv3 \
           KmeansTest_T1UCharRaw.nii.gz nefertiti.off fonts/Symbola_hint.ttf corpus/cgal/.complete corpus/assimp/.complete \
           corpus/geomview/.complete qt3d/.complete; do
    [ -e "$data/$f" ] || missing+=("$f")
  done
  if ((${#missing[@]})); then
    echo "assets: missing in assets/data/ (scripts/fetch_assets.sh fetches them): ${missing[*]}"
    exit 1
  fi
  echo "assets: all present in assets/data/"
  exit 0
fi
mkdir -p "$data"

fetch() {  # fetch PACKAGE PATH_IN_PACKAGE TARGET_NAME [PATH_IN_PACKAGE TARGET_NAME]...  (one download per call)
  local pkg="$1"; shift
  local args=("$@") missing=0 i
  for ((i = 1; i < ${#args[@]}; i += 2)); do [ -s "$data/${args[i]}" ] || missing=1; done
  [ "$missing" -eq 0 ] && return 0
  local tmp; tmp="$(mktemp -d)"
  echo "assets: fetching from Debian package $pkg"
  if ! (cd "$tmp" && apt-get download "$pkg" >/dev/null 2>&1); then
    [ "$(id -u)" -eq 0 ] && apt-get update -qq >/dev/null 2>&1 || true
    (cd "$tmp" && apt-get download "$pkg" >/dev/null) || { echo "assets: cannot download $pkg" >&2; rm -rf "$tmp"; return 1; }
  fi
  dpkg-deb -x "$tmp"/"$pkg"_*.deb "$tmp/x"
  for ((i = 0; i < ${#args[@]}; i += 2)); do
    local inner="${args[i]}" name="${args[i + 1]}"
    mkdir -p "$(dirname "$data/$name")"
    cp "$tmp/x/$inner" "$data/$name.part" && mv "$data/$name.part" "$data/$name"
  done
  rm -rf "$tmp"
}

fetch glmark2-data usr/share/glmark2/models/bunny.obj bunny.obj
[ "$mode" = --editor ] && exit 0
fetch gem-doc usr/share/gem/examples/data/venus.obj venus.obj
gltf2=usr/share/assimp/models/glTF2
fetch assimp-testmodels \
  $gltf2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf AnimatedMorphCube/AnimatedMorphCube.gltf \
  $gltf2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.bin AnimatedMorphCube/AnimatedMorphCube.bin \
  $gltf2/simple_skin/simple_skin.gltf simple_skin/simple_skin.gltf
fetch invesalius-examples usr/share/doc/invesalius-examples/examples/Cranium.inv3 Cranium.inv3
fetch insighttoolkit5-examples usr/share/doc/insighttoolkit5-examples/examples/Data/KmeansTest_T1UCharRaw.nii.gz \
  KmeansTest_T1UCharRaw.nii.gz

fetch fonts-symbola usr/share/fonts/truetype/ancient-scripts/Symbola_hint.ttf fonts/Symbola_hint.ttf

fetch_tree() {  # fetch_tree PACKAGE TARGET_DIR PATH_IN_PACKAGE... : copies folders of a package (all files below)
  local pkg="$1" name="$2" target="$data/$2"; shift 2
  [ -e "$target/.complete" ] && return 0
  local tmp; tmp="$(mktemp -d)"
  echo "assets: fetching $name from Debian package $pkg"
  (cd "$tmp" && apt-get download "$pkg" >/dev/null 2>&1) || { echo "assets: cannot download $pkg" >&2; rm -rf "$tmp"; return 1; }
  dpkg-deb -x "$tmp"/"$pkg"_*.deb "$tmp/x"
  rm -rf "$target" && mkdir -p "$target"
  local inner
  for inner in "$@"; do cp -r "$tmp/x/$inner" "$target/"; done
  touch "$target/.complete"
  rm -rf "$tmp"
}

# CGAL's demo data sit in a tarball inside the package: fetch it, then take the meshes out (nefertiti.off for the
# scenes, the whole folder for the loader corpus).
if [ ! -s "$data/nefertiti.off" ] || [ ! -e "$data/corpus/cgal/.complete" ]; then
  fetch libcgal-demo usr/share/doc/libcgal-dev/data.tar.gz cgal-data.tar.gz
  rm -rf "$data/corpus/cgal" && mkdir -p "$data/corpus/cgal"
  tar -xzf "$data/cgal-data.tar.gz" -C "$data/corpus/cgal" --strip-components=2 data/meshes
  cp "$data/corpus/cgal/nefertiti.off" "$data/nefertiti.off.part"
  mv "$data/nefertiti.off.part" "$data/nefertiti.off"
  rm -f "$data/cgal-data.tar.gz"
  touch "$data/corpus/cgal/.complete"
fi
models=usr/share/assimp/models
fetch_tree assimp-testmodels corpus/assimp $models/OBJ $models/PLY $models/OFF $models/STL
fetch_tree geomview corpus/geomview usr/share/geomview/geom
fetch_tree qt3d5-examples qt3d usr/lib/x86_64-linux-gnu/qt5/examples/qt3d/exampleresources/assets/.
echo "assets: $(ls "$data" | tr '\n' ' ')in assets/data/"
