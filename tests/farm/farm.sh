#!/usr/bin/env bash
# `trispline farm` for real: a 4-chunk array over assets/scenes/seed/walk.jsonl (frames 1-16 at 320×180, at most 2 tasks
# at once) on ENGINE = slurm (a single-node Slurm started here: slurmctld + slurmd from Debian's slurm-wlm, auth/none,
# state and spool under the test's folder, stopped by PID on exit) or local (the pool). Asserts: every frame and
# animation.glb equal one `replay --frames 1-16`'s bytes, two chunks overlapped in time and never more than 2 ran at
# once (task logs), `farm resume` after deleting one chunk's frames re-renders only that chunk, a failed chunk leaves
# the others intact and resume reruns it alone, a batch of three logs (one bad) is summarised into summary.json;
# a copy of the farm resumes into the copy, leaving the original untouched, and a batch log writing outside its run
# folder is that log's failure; local also: bad input is refused with nothing written, and a DFFD walk (topology
# changes) and a textured object (materials and images in the pieces) assemble exactly. A Slurm daemon that does not
# start fails the test with its log. Hostile farm folders and values: farm_hostile.sh.
# Usage: farm.sh slurm|local (TRISPLINE, TRISPLINE_SOURCE, FARM_OUT from ctest).
set -euo pipefail
engine=${1:?usage: farm.sh slurm|local}
exe=${TRISPLINE:?path of the trispline executable}
log=${TRISPLINE_SOURCE:?source tree}/assets/scenes/seed/walk.jsonl
out=${FARM_OUT:?output folder}/$engine
rm -rf "$out"
mkdir -p "$out"
size=(--width 320 --height 180)
farm=$out/farm
t0=$SECONDS

fail() {
  echo "FAIL: $*" >&2
  for f in "$farm"/logs/*.log; do [ -f "$f" ] && { echo "--- $f"; tail -n 20 "$f"; } >&2; done
  exit 1
}
status_json() { "$exe" farm status "$farm" --json; }

slurm_dir=$out/slurm
source "$(dirname "$0")/single_node_slurm.sh"

# Waits until the farm's jobs have left the queue (Slurm) — the local engine's submit and resume block.
wait_farm() {
  [ "$engine" = slurm ] || return 0
  for _ in $(seq 600); do
    [ -z "$(squeue -h -o %i 2>/dev/null)" ] && return 0
    sleep 0.25
  done
  squeue >&2 || true
  fail "the farm's jobs did not finish in 150 s"
}

check_frames_and_glb() {
  for f in "$out"/ref/frame_*.png; do
    cmp -s "$f" "$farm/$(basename "$f")" || fail "$(basename "$f") differs from the single-process reference"
  done
  cmp -s "$out/ref/animation.glb" "$farm/animation.glb" || fail "animation.glb differs from the single-process one"
}

if [ "$engine" = slurm ]; then
  start_slurm
  echo "slurm up in $((SECONDS - t0)) s"
fi

# The single-process reference.
"$exe" replay "$log" --frames 1-16 --out "$out/ref" --no-render "${size[@]}" > "$out/ref.txt"
[ "$(ls "$out"/ref/frame_*.png | wc -l)" = 16 ] || fail "the reference has not 16 frames"
echo "reference done at $((SECONDS - t0)) s"

if [ "$engine" = local ]; then
  # Bad input: a clear message, exit code 2, nothing written.
  expect_refused() {
    local want=$1; shift
    if "$exe" farm "$@" > "$out/refused.txt" 2>&1; then fail "accepted: farm $*"; fi
    grep -q -- "$want" "$out/refused.txt" ||
      { cat "$out/refused.txt" >&2; fail "no '$want' in the message of: farm $*"; }
    [ ! -e "$out/bad/farm.json" ] || fail "farm $* wrote farm.json"
  }
  expect_refused "chunk must be at least 1" submit "$log" --frames 1-16 --chunk 0 --out "$out/bad" --engine local
  expect_refused "--frames needs A-B" submit "$log" --frames 9-3 --chunk 4 --out "$out/bad" --engine local
  expect_refused "outside\|timeline" submit "$log" --frames 90-200 --chunk 4 --out "$out/bad" --engine local
  expect_refused "File does not exist" submit "$out/none.jsonl" --frames 1-4 --chunk 4 --out "$out/bad"
  if env PATH=/nonexistent "$exe" farm submit "$log" --frames 1-4 --chunk 4 --out "$out/bad" > "$out/refused.txt" 2>&1
  then fail "submitted to Slurm without sbatch"; fi
  grep -q "sbatch not found.*slurm-client" "$out/refused.txt" ||
    { cat "$out/refused.txt" >&2; fail "no sbatch message"; }
  [ ! -e "$out/bad/farm.json" ] || fail "a submission without sbatch wrote farm.json"
  echo "bad input refused at $((SECONDS - t0)) s"

  # The DFFD walk's bunny changes topology from frame 25: its pieces cannot be joined, the assembly poses every frame.
  bars=$TRISPLINE_SOURCE/assets/scenes/seed/bars_walk.jsonl
  "$exe" replay "$bars" --frames 21-28 --out "$out/bars_ref" --no-render --width 64 --height 36 > /dev/null
  "$exe" farm submit "$bars" --frames 21-28 --chunk 4 --out "$out/bars" --engine local --width 64 --height 36 \
    > "$out/bars.txt" || fail "the DFFD walk's farm failed: $(cat "$out/bars.txt")"
  jq -e '.record.glb_source == "posed"' "$out/bars/report.json" > /dev/null || fail "the DFFD walk's GLB was not posed"
  cmp -s "$out/bars_ref/animation.glb" "$out/bars/animation.glb" || fail "the DFFD walk's animation.glb differs"
  for f in "$out"/bars_ref/frame_*.png; do
    cmp -s "$f" "$out/bars/$(basename "$f")" || fail "the DFFD walk's $(basename "$f") differs"
  done
  echo "topology change assembled at $((SECONDS - t0)) s"

  # A textured object: the joined pieces carry its materials and images, byte for byte one replay's animation.glb.
  crate=$TRISPLINE_SOURCE/tests/farm/logs/textured_crate.jsonl
  "$exe" replay "$crate" --frames 1-4 --out "$out/crate_ref" --no-render --width 64 --height 36 > /dev/null
  "$exe" farm submit "$crate" --frames 1-4 --chunk 2 --out "$out/crate" --engine local --width 64 --height 36 \
    > "$out/crate.txt" || fail "the textured farm failed: $(cat "$out/crate.txt")"
  jq -e '.record.glb_source == "pieces"' "$out/crate/report.json" > /dev/null || fail "the crate's GLB was not joined"
  grep -qa '"image/png"' "$out/crate/animation.glb" || fail "the farm's animation.glb embeds no image"
  cmp -s "$out/crate_ref/animation.glb" "$out/crate/animation.glb" || fail "the textured animation.glb differs"
  echo "textured pieces assembled at $((SECONDS - t0)) s"
fi

# A chunk that fails (its folder cannot be made: a file is in the way) leaves the other chunks' frames intact, the
# assembly does not run (Slurm: afterok never satisfied), and resume reruns that chunk alone (Slurm: after cancelling
# the assemble job left waiting). The last chunk fails, so chunks 0 and 1 start together and both succeed: their task
# logs show the overlap checked below whatever the machine's speed (Slurm starts further tasks once a second).
mkdir -p "$farm/chunks"
touch "$farm/chunks/0003"
rc=0
"$exe" farm submit "$log" --frames 1-16 --chunk 4 --max-parallel 2 --out "$farm" --engine "$engine" "${size[@]}" \
  --time 00:10:00 > "$out/submit.txt" || rc=$?
cat "$out/submit.txt"
if [ "$engine" = local ]; then
  [ "$rc" = 1 ] || fail "submit exited $rc, not 1, with a failing chunk"
else
  [ "$rc" = 0 ] || fail "submit exited $rc"
  grep -q "submitted array job [0-9]* (tasks 0,1,2,3) and assemble job [0-9]* (afterok)" "$out/submit.txt" ||
    fail "submit did not print the job ids"
  grep -q "^#SBATCH --time=00:10:00" "$farm/farm_task.sh" || fail "the job script has no --time"
  for _ in $(seq 600); do  # until only the assemble job is left, waiting on its dependency
    [ -z "$(squeue -h -o '%i %r' | grep -v ' Dependency' || true)" ] && break
    sleep 0.25
  done
  case "$(squeue -h -o %r)" in  # Dependency, then DependencyNeverSatisfied once Slurm sees the failed task
    Dependency | DependencyNeverSatisfied) ;;
    *) squeue >&2; fail "the assemble job is not left waiting" ;;
  esac
fi
[ "$(status_json | jq -r '.tasks[3].state')" = failed ] || fail "task 3 is not reported failed"
[ "$(status_json | jq -r '.done')" = 3 ] || fail "the other 3 chunks are not done after one failed"
[ ! -e "$farm/animation.glb" ] || fail "assembled although a chunk failed"
for f in 1 2 3 4 5 6 7 8 9 10 11 12; do
  cmp -s "$out/ref/$(printf frame_%04d.png $f)" "$farm/chunks/000$(((f - 1) / 4))/$(printf frame_%04d.png $f)" ||
    fail "frame $f of a chunk that succeeded is not the reference's"
done
rm "$farm/chunks/0003"
"$exe" farm resume "$farm" > "$out/resume_failed.txt"
grep -q "tasks 3[,)]" "$out/resume_failed.txt" ||
  { cat "$out/resume_failed.txt"; fail "resume did not rerun task 3 only"; }
wait_farm  # Slurm: also the first assemble job, which resume cancelled
echo "farm done at $((SECONDS - t0)) s"

[ "$(status_json | jq -r '.done')" = 4 ] || { status_json; fail "not every chunk is done"; }
[ "$(status_json | jq -r '.assembled')" = true ] || { cat "$farm/logs/assemble.log"; fail "not assembled"; }
check_frames_and_glb
jq -e '.record.glb_source == "pieces"' "$farm/report.json" > /dev/null ||
  fail "animation.glb was not joined from pieces"

# Two chunks overlapped in time, and never more than --max-parallel 2 ran at once (the task logs' epoch times).
cat "$farm"/logs/task_*.log | awk '
  / start / { for (i = 1; i < NF; ++i) if ($i == "start") s[$3] = $(i + 1) }
  / exit / { for (i = 1; i < NF; ++i) if ($i == "end") e[$3] = $(i + 1) }
  END {
    n = 0; max = 0; overlap = 0
    for (a in s) for (b in s) if (a < b && s[a] < e[b] && s[b] < e[a]) overlap = 1
    for (a in s) { c = 0; for (b in s) if (s[b] <= s[a] && s[a] < e[b]) ++c; if (c > max) max = c; ++n }
    printf "tasks %d, overlapping %d, most at once %d\n", n, overlap, max
    exit !(n == 4 && overlap && max <= 2)
  }' || fail "the task logs do not show 4 tasks, two overlapping, at most 2 at once"

# Resume after deleting one chunk's frames: only that chunk runs again.
stamp() { stat -c '%n %i %Y' "$farm"/chunks/000[013]/frame_* "$farm"/logs/task_000[013].log; }
stamp > "$out/before.txt"
rm "$farm"/chunks/0002/frame_*.png
[ "$(status_json | jq -c '.missing_frames')" = "[9,10,11,12]" ] || fail "status does not list frames 9-12 missing"
[ "$(status_json | jq -r '.tasks[2].state')" = missing ] || fail "task 2 is not reported missing"
"$exe" farm resume "$farm" | tee "$out/resume.txt"
grep -q "tasks 2)\|tasks 2," "$out/resume.txt" || fail "resume did not resubmit task 2 alone"
wait_farm
stamp > "$out/after.txt"
cmp -s "$out/before.txt" "$out/after.txt" || fail "resume touched the frames or logs of chunks 0, 1, 3"
[ "$(status_json | jq -r '.done')" = 4 ] || fail "not every chunk is done after resume"
check_frames_and_glb
"$exe" farm resume "$farm" | grep -q "nothing to do" || fail "a second resume found something to do"

# A copy of the farm resumes into the copy (the scripts run in their folder; Slurm: sbatch --chdir of the copy), and
# the original is not touched.
stamp_farm() { find "$farm" -type f -printf '%P %i %s %T@\n' | sort; }
stamp_farm > "$out/before_copy.txt"
cp -r "$farm" "$out/copy"
rm "$out/copy"/chunks/0001/frame_*.png
"$exe" farm resume "$out/copy" > "$out/resume_copy.txt" || { cat "$out/resume_copy.txt"; fail "the copy's resume failed"; }
wait_farm
[ "$("$exe" farm status "$out/copy" --json | jq -r .assembled)" = true ] || fail "the copy is not assembled"
for f in "$out"/ref/frame_*.png; do
  cmp -s "$f" "$out/copy/$(basename "$f")" || fail "the copy's $(basename "$f") differs from the reference"
done
stamp_farm > "$out/after_copy.txt"
cmp -s "$out/before_copy.txt" "$out/after_copy.txt" || fail "resuming the copy touched the original farm"
echo "copied farm resumed at $((SECONDS - t0)) s"

# A batch: one task per log of a folder, every report.json in one summary (a failing log is a result: afterany).
mkdir -p "$out/library"
cp "$TRISPLINE_SOURCE"/tests/logs/{ring_animate,undo_redo,bad_unknown_command}.jsonl "$out/library/"
# A shared log that writes outside its run folder: refused by replay's output containment, a failure of that log.
printf '%s\n' '{"cmd":"volume.load","analytic":"sphere","name":"ball"}' \
  '{"cmd":"volume.export","object":"ball","what":"silhouettes","path":"../../../escaped_by_log.svg"}' \
  > "$out/library/escape.jsonl"
rc=0
"$exe" farm batch "$out/library" --out "$out/batch" --engine "$engine" --max-parallel 2 "${size[@]}" \
  > "$out/batch.txt" || rc=$?
if [ "$engine" = local ]; then
  [ "$rc" = 1 ] || fail "farm batch exited $rc, not 1, although a log fails"
  grep -q "^assembled: " "$out/batch.txt" || fail "the batch was not summarised: $(cat "$out/batch.txt")"
else
  [ "$rc" = 0 ] && grep -q "assemble job [0-9]* (afterany)" "$out/batch.txt" ||
    fail "farm batch did not submit an afterany assembly: $(cat "$out/batch.txt")"
  wait_farm
fi
jq -e '.logs == 4 and .ok == 2 and .failed == ["bad_unknown_command", "escape"] and
       ([.runs[] | select(.ok) | .report.final_png] | length == 2) and
       ([.runs[] | select(.name == "escape") | .error | test("output folder")] == [true])' \
  "$out/batch/summary.json" > /dev/null ||
  { cat "$out/batch/summary.json" "$out/batch/logs/assemble.log" >&2; fail "the batch summary is not 4 logs, 2 ok"; }
[ -z "$(find "$(dirname "$out")" -name 'escaped_by_log*')" ] || fail "a batch log wrote outside its run folder"
[ -f "$out/batch/runs/ring_animate/final.png" ] || fail "the batch did not render ring_animate"
echo "batch done at $((SECONDS - t0)) s"

echo "PASS farm.$engine in $((SECONDS - t0)) s"
