#!/usr/bin/env bash
# `trispline bench editor` end to end under this Xvfb (tests/with_xvfb.sh): the real editor opens each scene (the
# default scene, a tiled teapot, the small T1 MRI with its silhouettes) and times idle and orbiting frames, Blender
# 3.4 redraws the same meshes (scripts/blender_redraw_timer.py), and the recording with a hidden volume is replayed
# twice. Asserts what the run must give — every scene, a positive frame time for each phase, Blender's figures and
# its vertex count, silhouettes extracted while orbiting, the recording ratio — never a timing bound.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out="${GUI_OUT:-/tmp}/bench_editor"
rm -rf "$out"
mkdir -p "$out"
cd "$root"
"$TRISPLINE" bench editor --json --frames 3 --work "$out/work" --volume assets/data/KmeansTest_T1UCharRaw.nii.gz \
  --iso 46.8 > "$out/bench.json"
cat "$out/bench.json"
check() {
  if ! jq -e "$1" "$out/bench.json" > /dev/null; then
    echo "FAIL: $2 ($1)" >&2
    exit 1
  fi
  echo "ok: $2"
}
check '.bench == "editor" and ([.scenes[].name] == ["default", "tiles", "volume"])' "the three scenes, in order"
check 'all(.scenes[]; .idle_median_ms > 0 and .orbit_median_ms > 0 and .orbit_p95_ms >= .orbit_median_ms)' \
  "idle and orbit frame times of every scene"
check 'all(.scenes[]; .blender_redraw_ms > 0 and .blender_orbit_median_ms > 0 and .blender_vertices > 0)' \
  "Blender's redraw of every scene's meshes"
check '(.scenes[1].blender_vertices > 500000)' "the tiled teapot reaches Blender with its tiles"
check '(.scenes[2].silhouette_results >= 1 and .scenes[2].silhouette_median_ms > 0)' \
  "silhouettes extracted while the volume orbits"
check '(.record_hidden_volume_ratio > 0 and .record_ms_per_frame.without > 0)' "the recording ratio"
echo PASS
