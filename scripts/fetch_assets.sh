#!/usr/bin/env bash
# Fetches the real input meshes from Debian data packages into assets/data/ (git-ignored; never commit them):
#   glmark2-data → bunny.obj (Stanford bunny, 34,835 vertices); gem-doc → venus.obj (Venus bust, 711 vertices).
# Uses `apt-get download` + `dpkg-deb -x`: nothing is installed. Idempotent: does nothing when the files exist.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="$root/assets/data"
mkdir -p "$data"

fetch() {  # fetch PACKAGE PATH_IN_PACKAGE TARGET_NAME
  local pkg="$1" inner="$2" name="$3"
  [ -s "$data/$name" ] && return 0
  local tmp; tmp="$(mktemp -d)"
  echo "assets: fetching $name from Debian package $pkg"
  if ! (cd "$tmp" && apt-get download "$pkg" >/dev/null 2>&1); then
    [ "$(id -u)" -eq 0 ] && apt-get update -qq >/dev/null 2>&1 || true
    (cd "$tmp" && apt-get download "$pkg" >/dev/null) || { echo "assets: cannot download $pkg" >&2; rm -rf "$tmp"; return 1; }
  fi
  dpkg-deb -x "$tmp"/"$pkg"_*.deb "$tmp/x"
  cp "$tmp/x/$inner" "$data/$name.part" && mv "$data/$name.part" "$data/$name"
  rm -rf "$tmp"
}

fetch glmark2-data usr/share/glmark2/models/bunny.obj bunny.obj
fetch gem-doc usr/share/gem/examples/data/venus.obj venus.obj
echo "assets: $(ls "$data" | tr '\n' ' ')in assets/data/"
