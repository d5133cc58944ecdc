#!/usr/bin/env bash
# Installs what trispline needs (Debian packages, idempotent and quick when already installed), fetches the real
# meshes into assets/data/ (git-ignored), and builds into build/. Usage: scripts/setup.sh [--no-build]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

mapfile -t wanted < <(grep -v '^#' scripts/packages.txt | tr ' ' '\n' | sed '/^$/d')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#wanted[@]} Debian packages present"
fi

scripts/fetch_assets.sh

if [ "${1:-}" != "--no-build" ]; then
  build_type="${TRISPLINE_BUILD_TYPE:-RelWithDebInfo}"
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type" > build.log.tmp 2>&1 || { cat build.log.tmp; rm -f build.log.tmp; exit 1; }
  rm -f build.log.tmp
  echo "setup: building (build/, $(nproc) jobs)…"
  cmake --build build -j"$(nproc)"
fi
