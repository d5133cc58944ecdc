#!/usr/bin/env bash
# Regenerates the README pictures with trispline's own rendering: the editor under Xvfb (docs/images/editor.png)
# and the headless replay of the default scene (docs/images/default_scene.png). Needs a build (scripts/setup.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
xvfb-run -a -s "-screen 0 1600x900x24" build/editor/trispline edit assets/scenes/seed/walk.jsonl --no-recover \
  --screenshot docs/images/editor.png
build/editor/trispline replay assets/scenes/default.jsonl --out out/readme --width 960 --height 540 >/dev/null
cp out/readme/final.png docs/images/default_scene.png
echo "wrote docs/images/editor.png docs/images/default_scene.png"
