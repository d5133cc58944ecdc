#!/usr/bin/env bash
# The sanitizer and fuzz runs CI makes after the test command (docs/decisions.md "Sanitizers and fuzzing in CI"):
#   1. builds core, the command layer, their tests and the libFuzzer targets with clang under AddressSanitizer +
#      UndefinedBehaviorSanitizer into build-asan/ (no GUI: the GL layers run in the plain build's tests);
#   2. runs the core and command tests and every fuzz target's seeds and regression files once (ctest);
#   3. fuzzes the targets two at a time within one shared budget, TRISPLINE_FUZZ_BUDGET seconds of wall time (default
#      160: each target gets budget × jobs / targets seconds, 24 s for 13 targets on 2 cores), or each for
#      TRISPLINE_FUZZ_SECONDS when set (at most a target's own SECONDS when tests/fuzz/CMakeLists.txt gives one; seed
#      TRISPLINE_FUZZ_SEED, default 1). A crash fails the run
#      and leaves the input in build-asan/fuzz/<target>/crashes/; add it to tests/fuzz/regressions/<target>/ with the
#      fix.
# Usage: scripts/sanitize.sh [--build] [--test] [--fuzz]   (all three when none is given; --no-fuzz = --build --test,
#        --fuzz-only = --fuzz; run scripts/setup.sh --tests --no-build first on a fresh machine)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1  # hits across clones and worktrees
build=build-asan
budget="${TRISPLINE_FUZZ_BUDGET:-160}"
# A fixed seed by default: CI explores the same mutations each run, so a red run is a regression, not luck; 0 = a
# random seed per run (longer local runs: TRISPLINE_FUZZ_SEED=0 TRISPLINE_FUZZ_SECONDS=3600).
fuzz_seed="${TRISPLINE_FUZZ_SEED:-1}"
jobs="$(nproc)"

do_build=0 do_test=0 do_fuzz=0
for arg in "$@"; do
  case "$arg" in
    --build) do_build=1 ;;
    --test) do_test=1 ;;
    --fuzz | --fuzz-only) do_fuzz=1 ;;
    --no-fuzz) do_build=1 do_test=1 ;;
    *) echo "sanitize: unknown option '$arg' (--build, --test, --fuzz, --no-fuzz, --fuzz-only)" >&2; exit 2 ;;
  esac
done
((do_build || do_test || do_fuzz)) || do_build=1 do_test=1 do_fuzz=1

log="$build/sanitize-build.log"
mkdir -p "$build"
start=$SECONDS
if ((do_build)); then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" -DCMAKE_C_FLAGS_SANITIZE="-O1 -gline-tables-only" \
    -DTRISPLINE_BUILD_GUI=OFF -DTRISPLINE_FUZZ=ON > "$log" 2>&1 || { cat "$log"; exit 1; }
  echo "sanitize: building ($build/, ASan + UBSan + libFuzzer coverage, $jobs jobs)…"
  cmake --build "$build" -j"$jobs" >> "$log" 2>&1 || { tail -n 60 "$log"; exit 1; }
  echo "sanitize: built in $((SECONDS - start)) s"
fi

# abort_on_error: a finding ends the test with a signal; detect_leaks: leaks are findings too.
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp:print_suppressions=0"  # third-party leaks, each explained
if ((do_test)); then
  start=$SECONDS
  ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 900 -L 'core|fuzz-regress'
  echo "sanitize: core, command and fuzz-regression tests in $((SECONDS - start)) s"
fi

((do_fuzz)) || exit 0

# Each target fuzzes from a fresh working corpus seeded by its seed folders (the seeds themselves are never written).
start=$SECONDS
fuzz_one() {
  local target="$1" dir="$build/fuzz/$1" secs="$seconds" cap
  if [ -f "$build/tests/fuzz/$target.seconds" ]; then
    cap="$(cat "$build/tests/fuzz/$target.seconds")"
    if ((cap < secs)); then secs="$cap"; fi
  fi
  rm -rf "$dir" && mkdir -p "$dir/corpus" "$dir/crashes"
  local seeds
  read -r -a seeds < <(tr ';' ' ' < "$build/tests/fuzz/$target.seeds"; echo)
  if "$build/tests/fuzz/$target" "$dir/corpus" "${seeds[@]}" -max_total_time="$secs" -seed="$fuzz_seed" -max_len=65536 \
       -rss_limit_mb=2048 -timeout=20 -artifact_prefix="$dir/crashes/" -print_final_stats=1 > "$dir/log.txt" 2>&1; then
    echo "fuzz: $target: ${secs} s, $(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$dir/log.txt" | grep -o '[0-9]*$') runs, no crash"
  else
    echo "fuzz: $target FAILED — input in $dir/crashes/:"
    ls "$dir/crashes"
    grep -A40 -m1 -E 'ERROR: |==[0-9]+==|deadly signal|abort' "$dir/log.txt" | head -60
    return 1
  fi
}
mapfile -t targets < "$build/fuzz_targets.txt"
seconds="${TRISPLINE_FUZZ_SECONDS:-$((budget * jobs / ${#targets[@]}))}"
status=0
pids=()
for t in "${targets[@]}"; do
  fuzz_one "$t" & pids+=($!)
  if ((${#pids[@]} >= jobs)); then wait "${pids[0]}" || status=1; pids=("${pids[@]:1}"); fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
echo "sanitize: fuzzed ${#targets[@]} targets for at most ${seconds} s each in $((SECONDS - start)) s"
exit $status
