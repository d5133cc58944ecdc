#!/usr/bin/env bash
# The test command (README; CI runs it): set up, build, run every test with ctest.
# GL tests run for real on Mesa's llvmpipe through EGL; they fail (never skip) when no context can be made.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/setup.sh
scripts/test_tools.sh
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$root/build/mesa_shader_cache}"
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
