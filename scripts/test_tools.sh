#!/usr/bin/env bash
# Installs the real clients the `clients` tests run on trispline's exports (test-only: scripts/setup.sh installs what
# the editor needs). Idempotent and quick when present:
#   Blender 3.4 (Debian packages in scripts/test_packages.txt, ~200 MB with dependencies, ~30 s with a warm apt cache);
#   Node.js (Debian `nodejs` + `npm`, unless a node and npm are already on PATH) and the Khronos glTF validator, npm
#   `gltf-validator` pinned below, into build/test-tools/node_modules (~2 s).
# The tests fail (never skip) when a client is missing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
validator_version=2.0.0-dev.3.10

mapfile -t wanted < <(grep -v '^#' scripts/test_packages.txt | tr ' ' '\n' | sed '/^$/d')
command -v node >/dev/null || wanted+=(nodejs)
command -v npm >/dev/null || wanted+=(npm)
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "test tools: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

tools="$root/build/test-tools"
installed="$tools/node_modules/gltf-validator/package.json"
if [ ! -f "$installed" ] || ! grep -q "\"version\": \"$validator_version\"" "$installed"; then
  echo "test tools: installing gltf-validator@$validator_version into $tools"
  mkdir -p "$tools"
  npm install --prefix "$tools" --no-audit --no-fund --no-save "gltf-validator@$validator_version" >/dev/null
fi
echo "test tools: $(blender --version 2>/dev/null | head -1), node $(node --version), gltf-validator $validator_version"
