#!/usr/bin/env bash
# The test command (README; CI runs it): set up, build, run every test with ctest.
# GL tests run for real on Mesa's llvmpipe through EGL; they fail (never skip) when no context can be made.
# ctest runs one job more than cores: two of them may be window tests, which mostly wait on their editors' frames.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
start=$SECONDS
scripts/setup.sh --tests
scripts/test_tools.sh
echo "test: set up and built in $((SECONDS - start)) s"
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$root/build/mesa_shader_cache}"
start=$SECONDS
status=0
ctest --test-dir build --output-on-failure -j"$(($(nproc) + 1))" --timeout 600 || status=$?
echo "test: ctest in $((SECONDS - start)) s"
exit "$status"
