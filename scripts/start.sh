#!/usr/bin/env bash
# The first command of the README: installs what is needed, builds, and opens the editor on the default scene
# (the Utah teapot with the Stanford bunny draped along a stroke over its body). Without a display it replays the
# default scene headlessly and prints where the image, the exported scene and the report went.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/setup.sh
scene="assets/scenes/default.jsonl"
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec build/editor/trispline edit "$scene" "$@"
fi
echo "start: no display found — replaying $scene headlessly"
exec build/editor/trispline replay "$scene" --out out/default "$@"
