#!/usr/bin/env bash
# Installs what trispline needs (Debian packages, idempotent and quick when already installed), fetches the real
# meshes into assets/data/ (git-ignored), and builds into build/.
#   scripts/setup.sh            the editor's packages (scripts/packages.txt), then builds the editor only
#   scripts/setup.sh --tests    also the tests' packages (scripts/test_packages.txt), then builds everything
#   scripts/setup.sh --no-build packages and assets only (combine with --tests)
#   scripts/setup.sh --check    says what is missing (packages, assets) without installing anything; exit 1 if any
# Build type: TRISPLINE_BUILD_TYPE (RelWithDebInfo). The build shows its step n/N; each phase prints its time.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
tests=0 build=1 check=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    --no-build) build=0 ;;
    --check) check=1 ;;
    *) echo "setup: unknown option '$arg' (--tests, --no-build, --check)" >&2; exit 2 ;;
  esac
done
phase_start=$SECONDS
phase_done() { echo "setup: $1 in $((SECONDS - phase_start)) s"; phase_start=$SECONDS; }

lists=(scripts/packages.txt)
((tests || check)) && lists+=(scripts/test_packages.txt)
missing=()
for list in "${lists[@]}"; do
  mapfile -t wanted < <(grep -v '^#' "$list" | tr ' ' '\n' | sed '/^$/d')
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
done
if ((check)); then
  status=0
  editor_missing=() test_missing=()
  for p in "${missing[@]}"; do
    if grep -v '^#' scripts/packages.txt | tr ' ' '\n' | grep -qx "$p"; then editor_missing+=("$p"); else test_missing+=("$p"); fi
  done
  if ((${#editor_missing[@]})); then
    echo "setup: missing for the editor (scripts/packages.txt): ${editor_missing[*]}"; status=1
  else
    echo "setup: the editor's packages are all installed"
  fi
  if ((${#test_missing[@]})); then
    echo "setup: missing for the tests (scripts/test_packages.txt): ${test_missing[*]}"; status=1
  else
    echo "setup: the tests' packages are all installed"
  fi
  ((status)) && echo "setup: install them with: sudo apt-get install --no-install-recommends ${missing[*]}"
  scripts/fetch_assets.sh --check || status=1
  exit "$status"
fi
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
  phase_done "packages installed"
else
  echo "setup: all Debian packages present"
fi

if ((tests)); then scripts/fetch_assets.sh; else scripts/fetch_assets.sh --editor; fi
phase_done "assets"

if ((build)); then
  build_type="${TRISPLINE_BUILD_TYPE:-RelWithDebInfo}"
  # Tests on only when their packages are here: the editor's own build never needs GoogleTest or Xvfb. Turning them
  # on later (scripts/test.sh) adds targets and rebuilds none of the editor's objects.
  build_tests=OFF
  if ((tests)) || grep -q '^TRISPLINE_BUILD_TESTS:BOOL=ON' build/CMakeCache.txt 2>/dev/null; then build_tests=ON; fi
  # The core tests run in the sanitizer build (scripts/test.sh); build/ keeps the FFD kernel tests only, unless the
  # folder was configured otherwise (-DTRISPLINE_BUILD_CORE_TESTS=ON: every test in build/ as well).
  core_tests=()
  grep -q '^TRISPLINE_BUILD_CORE_TESTS:' build/CMakeCache.txt 2>/dev/null || core_tests=(-DTRISPLINE_BUILD_CORE_TESTS=OFF)
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type" -DTRISPLINE_BUILD_TESTS="$build_tests" \
    "${core_tests[@]}" > build.log.tmp 2>&1 || { cat build.log.tmp; rm -f build.log.tmp; exit 1; }
  rm -f build.log.tmp
  phase_done "configured"
  target=(); ((tests)) || target=(--target trispline)
  echo "setup: building ${target[*]:-everything} (build/, $(nproc) jobs)…"
  cmake --build build -j"$(nproc)" "${target[@]}"
  phase_done "built"
fi
