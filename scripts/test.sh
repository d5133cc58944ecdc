#!/usr/bin/env bash
# The test command (README; CI runs it): set up, build, run every test with ctest.
#   build/       the plain build scripts/start.sh makes (its objects are reused): the editor, GL, GUI, scene, farm and
#                client tests and the FFD kernel tests. GL tests run for real on Mesa's llvmpipe through EGL; they fail
#                (never skip) when no context can be made. ctest runs one job more than cores: two of them may be
#                window tests, which mostly wait on their editors' frames.
#   build-asan/  the sanitizer build (scripts/sanitize.sh: clang, ASan + UBSan): the core and command tests and the
#                fuzz targets' seeds and regression files. It builds and runs beside the plain build at nice 19, on
#                the CPU time the plain build and the window tests leave idle; its output is printed at the end.
# Each phase prints its time. Exit status: non-zero when any test of either build failed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
start=$SECONDS
scripts/setup.sh --tests --no-build
scripts/test_tools.sh
echo "test: packages, assets and test tools in $((SECONDS - start)) s"

mkdir -p build-asan
( nice -n 19 scripts/sanitize.sh --build --test > build-asan/test.log 2>&1 ) &
sanitizer=$!
start=$SECONDS
scripts/setup.sh --tests
echo "test: plain build in $((SECONDS - start)) s"

export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$root/build/mesa_shader_cache}"
start=$SECONDS
status=0
ctest --test-dir build --output-on-failure -j"$(($(nproc) + 1))" --timeout 600 || status=$?
echo "test: ctest of build/ in $((SECONDS - start)) s"

start=$SECONDS
sanitizer_status=0
wait "$sanitizer" || sanitizer_status=$?
echo "test: waited $((SECONDS - start)) s for the sanitizer build and its tests (build-asan/test.log):"
cat build-asan/test.log
((status)) || status=$sanitizer_status
exit "$status"
