#!/usr/bin/env bash
# The first command of the README: installs what is needed, builds, and opens the editor on the default scene
# (the Utah teapot with the Stanford bunny draped along a stroke over its body). Without a display (or when the
# display cannot be opened) it replays the default scene headlessly and prints where the image, the exported scene
# and the report went.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/setup.sh
scene="assets/scenes/default.jsonl"
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  status=0
  build/editor/trispline edit "$scene" "$@" || status=$?
  [ "$status" -ne 2 ] && exit "$status"   # 2 = no window could be created: fall back to the headless replay
  echo "start: the display could not be opened"
fi
echo "start: no display — replaying $scene headlessly"
exec build/editor/trispline replay "$scene" --out out/default
