#!/usr/bin/env bash
# Render-farm benchmark (figures only, never asserted): frames per minute of a recording in one process and through
# `trispline farm` by engine and parallelism, and each chunk's overhead (task start → its first frame on disk).
# Usage: bench/farm.sh [TRISPLINE] [--frames 1-96] [--chunk 24] [--size 1280x720] [--engines "single local:1 local:2
# slurm:2"]. slurm:N starts the tests' single-node Slurm (tests/farm/single_node_slurm.sh; root). Output in
# build/bench_farm/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exe=$root/build/editor/trispline
frames=1-96 chunk=24 size=1280x720 engines="single local:1 local:2 slurm:2"
while (($#)); do
  case $1 in
    --frames) frames=$2; shift 2 ;;
    --chunk) chunk=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --engines) engines=$2; shift 2 ;;
    *) exe=$1; shift ;;
  esac
done
log=$root/assets/scenes/seed/walk.jsonl
out=$root/build/bench_farm
rm -rf "$out"
mkdir -p "$out"
wh=(--width "${size%x*}" --height "${size#*x}")
n=$(( ${frames#*-} - ${frames%-*} + 1 ))
now() { date +%s.%N; }
fpm() { awk -v n="$n" -v s="$1" 'BEGIN { printf "%.1f", n * 60 / s }'; }

# Per chunk: seconds from the task's start line to its first frame file's mtime, and its replay of the log.
overhead() {
  local dir=$1
  for l in "$dir"/logs/task_*.log; do
    local k start first
    k=$(basename "$l" .log); k=${k#task_}
    start=$(awk '/ start / { for (i = 1; i < NF; ++i) if ($i == "start") print $(i + 1) }' "$l")
    first=$(ls "$dir/chunks/$k"/frame_* | head -1)
    awk -v s="$start" -v f="$(stat -c %.9Y "$first")" -v r="$(jq .replay_ms "$dir/chunks/$k/report.json")" \
      -v k="$k" 'BEGIN { printf "    chunk %s: first frame %.2f s after the task started (log replay %.2f s)\n",
                              k, f - s, r / 1000 }'
  done
}

echo "walk.jsonl frames $frames ($n) at $size, chunks of $chunk, $(nproc) CPUs, $(date -u '+%Y-%m-%d %H:%M UTC')"
single_s=""
for e in $engines; do
  name=${e%%:*} par=${e#*:}
  if [ "$name" = single ]; then
    t=$(now)
    "$exe" replay "$log" --frames "$frames" --out "$out/single" --no-render "${wh[@]}" > /dev/null
    s=$(awk -v a="$t" -v b="$(now)" 'BEGIN { print b - a }')
    single_s=$s
    echo "  single process: $(printf %.1f "$s") s, $(fpm "$s") frames/min"
    continue
  fi
  dir=$out/$name$par
  if [ "$name" = slurm ] && [ -z "${SLURM_CONF:-}" ]; then
    slurm_dir=$out/slurm
    source "$root/tests/farm/single_node_slurm.sh"
    start_slurm
  fi
  t=$(now)
  "$exe" farm submit "$log" --frames "$frames" --chunk "$chunk" --out "$dir" --engine "$name" --max-parallel "$par" \
    "${wh[@]}" > "$out/$name$par.txt"
  if [ "$name" = slurm ]; then
    while [ -n "$(squeue -h -o %i)" ]; do sleep 0.2; done
  fi
  s=$(awk -v a="$t" -v b="$(now)" 'BEGIN { print b - a }')
  asm=$(grep -o 'assembled frames.*' "$dir/logs/assemble.log" || true)
  echo "  $name, $par at once: $(printf %.1f "$s") s (submission to assembled), $(fpm "$s") frames/min" \
    "${single_s:+($(awk -v a="$s" -v b="$single_s" 'BEGIN { printf "%.2f", a / b }')× single)}"
  first_start=$(cat "$dir"/logs/task_*.log |
    awk '/ start / { for (i = 1; i < NF; ++i) if ($i == "start") print $(i + 1) }' | sort -n | head -1)
  awk -v a="$t" -v b="$first_start" 'BEGIN { printf "    submission to the first task start: %.2f s\n", b - a }'
  overhead "$dir"
  [ -n "$asm" ] && echo "    $asm"
done
