#!/usr/bin/env bash
# `trispline farm` on hostile input, with the local pool on a tiny scene (tests/logs/record_anim.jsonl, frames 1-10 in
# chunks of 2 at 32×24). Asserts: values that would end a job script's line (a newline in --partition or --time) are
# refused with exit 2 naming the option, and a newline in the --out folder's name runs nothing; every bad CLI value
# exits 2; a farm.json with chunk 0, a task's last frame 2^31−1 or a dropped task is refused (exit 2 naming the key,
# no crash, status bounded); an empty, garbage or swapped frame and a patched animation.piece are never "assembled"
# and resume re-renders only that chunk; a log edited after submission is refused by status, assemble and resume; a
# copied farm resumes into the copy (the original untouched) and a moved farm resumes where it is; a SIGKILLed pool's
# replays die with it and resume runs each chunk once; resume stops a task a killed pool left running; a frame over
# the 64-megapixel budget exits 2 before anything is written; a batch's tampered report is not a run and its logs
# edited after submission are refused.
# Usage: farm_hostile.sh (TRISPLINE, TRISPLINE_SOURCE, FARM_OUT from ctest).
set -euo pipefail
exe=${TRISPLINE:?path of the trispline executable}
out=${FARM_OUT:?output folder}/hostile
rm -rf "$out"
mkdir -p "$out"
out=$(cd "$out" && pwd -P)  # as /proc/PID/cwd shows it
log=$out/scene.jsonl
cp "${TRISPLINE_SOURCE:?source tree}/tests/logs/record_anim.jsonl" "$log"
size=(--width 32 --height 24)
t0=$SECONDS

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
status_of() { "$exe" farm status "$1" --json; }
assembled() { [ "$(status_of "$1" | jq -r .assembled)" = true ]; }
# expect_exit CODE WANT CMD…: CMD exits CODE and prints WANT (grep pattern).
expect_exit() {
  local code=$1 want=$2 rc=0
  shift 2
  "$@" > "$out/msg.txt" 2>&1 || rc=$?
  [ "$rc" = "$code" ] || { cat "$out/msg.txt" >&2; fail "exit $rc, not $code: $*"; }
  grep -q -- "$want" "$out/msg.txt" || { cat "$out/msg.txt" >&2; fail "no '$want' in the message of: $*"; }
}
submit() { "$exe" farm submit "$1" --frames 1-10 --chunk 2 --out "$2" --engine local "${size[@]}" > "$2.txt" 2>&1; }

# Values that end a line of the job script: refused before anything is written; nothing runs.
expect_exit 2 "--partition" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/p" --engine local \
  --partition $'farm\ntouch '"$out/pwned_partition"
expect_exit 2 "--time" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/p" --engine local \
  --time $'00:10:00\ntouch '"$out/pwned_time"
expect_exit 2 "--partition" "$exe" farm batch "$out" --out "$out/p" --engine local --partition $'a\rb'
[ ! -e "$out/p/farm.json" ] || fail "a refused submission wrote farm.json"
# A newline in the farm folder's name: its path is in no script (they run in the folder), so the farm just works.
nl_dir="$out/"$'nl\ntouch '"$out/pwned_out"
"$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$nl_dir" --engine local "${size[@]}" > "$out/nl.txt" 2>&1 ||
  { cat "$out/nl.txt" >&2; fail "the farm in a folder named with a newline failed"; }
assembled "$nl_dir" || fail "the farm in a folder named with a newline is not assembled"
expect_exit 2 "--out" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/"$'s\nx' --engine slurm
ls "$out"/pwned_* > /dev/null 2>&1 && fail "a value in a job script ran as a command"
# Every bad value exits 2 (the documented code), with CLI11's or the farm's message.
expect_exit 2 "max-parallel" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/p" --max-parallel -1
expect_exit 2 "chunk" "$exe" farm submit "$log" --frames 1-2 --chunk abc --out "$out/p"
expect_exit 2 "chunk" "$exe" farm submit "$log" --frames 1-2 --chunk 99999999999 --out "$out/p"
expect_exit 2 "width" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/p" --width 0 --height 24
expect_exit 2 "engine" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/p" --engine pbs
expect_exit 2 "dir" "$exe" farm status "$out/none"
# A frame over the 64-megapixel budget of anim.record: refused before farm.json is written, as by replay.
expect_exit 2 "megapixels" "$exe" farm submit "$log" --frames 1-2 --chunk 1 --out "$out/big" --engine local \
  --width 16384 --height 16384
[ ! -e "$out/big/farm.json" ] || fail "a frame over the budget wrote farm.json"
expect_exit 2 "megapixels" "$exe" replay "$log" --out "$out/big_replay" --width 16384 --height 16384
[ ! -e "$out/big_replay/report.json" ] || fail "replay ran with a frame over the budget"
touch "$out/a_file"
expect_exit 2 "is a file" "$exe" farm submit "$log" --frames 1-2 --chunk 2 --out "$out/a_file" --engine local
expect_exit 2 "index" "$exe" farm task "$out" 999999
echo "script values and CLI values refused at $((SECONDS - t0)) s"

# The reference farm.
farm=$out/farm
submit "$log" "$farm" || { cat "$farm.txt" >&2; fail "the reference farm failed"; }
assembled "$farm" || fail "the reference farm is not assembled"
stamp() { find "$1" -type f -printf '%P %i %s %T@\n' | sort; }
stamp "$farm" > "$out/farm_before.txt"
echo "reference farm at $((SECONDS - t0)) s"

# farm.json that is not a plan: every command refuses it naming the key, and nothing is written.
bad_plan() {  # bad_plan NAME JQ KEY
  cp -r "$farm" "$out/$1"
  jq "$2" "$farm/farm.json" > "$out/$1/farm.json"
  stamp "$out/$1" > "$out/$1.before"
  local cmds=(status)
  [ "$1" = chunk0 ] && cmds=(status resume assemble)  # chunk 0 once divided by zero in assemble and resume
  for cmd in "${cmds[@]}"; do
    expect_exit 2 "key '$3'" timeout 60 "$exe" farm "$cmd" "$out/$1"
  done
  expect_exit 2 "key '$3'" bash "$out/$1/farm_task.sh" < /dev/null  # the job script as a node runs it
  stamp "$out/$1" > "$out/$1.after"
  cmp -s "$out/$1.before" "$out/$1.after" || fail "a refused plan ($1) changed its folder"
}
export SLURM_ARRAY_TASK_ID=0
bad_plan chunk0 '.chunk = 0' chunk
bad_plan huge_last '.tasks[1].last = 2147483647' 'tasks\[1\].last'
bad_plan dropped_task 'del(.tasks[1])' tasks
bad_plan escape_log '.log = "scene.jsonl"' log
unset SLURM_ARRAY_TASK_ID
echo "bad plans refused at $((SECONDS - t0)) s"

# Damaged chunk files in a copy of the farm (a copy resumes into itself): a frame swapped for another valid one, a
# patched animation.piece, a garbage frame, an empty frame. Never assembled; the damaged chunks alone re-rendered;
# the result the reference's bytes; the original untouched.
cp -r "$farm" "$out/damaged"
(
  cd "$out/damaged/chunks"
  cp 0000/frame_0002.png 0000/frame_0001.png
  printf '\377\377\300\177' | dd of=0001/animation.piece bs=1 seek=64 conv=notrunc status=none
  head -c 300 /dev/urandom > 0003/frame_0007.png
  truncate -s 0 0004/frame_0010.png
)
status_of "$out/damaged" > "$out/damaged.json"
jq -e '.assembled == false and ([.tasks[].state] == ["missing", "missing", "done", "missing", "missing"]) and
       .missing_frames == [1, 7, 10]' "$out/damaged.json" > /dev/null ||
  { cat "$out/damaged.json" >&2; fail "status does not find the damaged chunks 0, 1, 3, 4"; }
expect_exit 2 "chunk 0000" "$exe" farm assemble "$out/damaged"
[ ! -e "$out/damaged/report.json" ] || fail "a refused assembly left report.json"
"$exe" farm resume "$out/damaged" > "$out/damaged.txt" 2>&1 || { cat "$out/damaged.txt" >&2; fail "resume failed"; }
grep -q "tasks 0,1,3,4, at most" "$out/damaged.txt" || { cat "$out/damaged.txt" >&2; fail "not tasks 0,1,3,4 alone"; }
assembled "$out/damaged" || fail "the damaged copy is not assembled after resume"
for f in "$farm"/frame_*.png "$farm/animation.glb"; do
  cmp -s "$f" "$out/damaged/$(basename "$f")" || fail "the resumed copy's $(basename "$f") differs from the reference"
done
# A chunk without its task's record (the task never finished) is not done either.
cp -r "$farm" "$out/unrecorded"
rm "$out/unrecorded/chunks/0002/chunk.json"
[ "$(status_of "$out/unrecorded" | jq -c '[.assembled, .tasks[2].state]')" = '[false,"missing"]' ] ||
  fail "a chunk without chunk.json counts as done"
stamp "$farm" > "$out/farm_after.txt"
cmp -s "$out/farm_before.txt" "$out/farm_after.txt" || fail "resuming the copy touched the original farm"
echo "damaged chunks re-rendered at $((SECONDS - t0)) s"

# A moved farm resumes where it is.
cp -r "$farm" "$out/to_move"
mv "$out/to_move" "$out/moved"
rm "$out/moved"/chunks/0001/frame_*.png
"$exe" farm resume "$out/moved" > "$out/moved.txt" 2>&1 || { cat "$out/moved.txt" >&2; fail "the moved farm's resume failed"; }
assembled "$out/moved" || fail "the moved farm is not assembled"
[ ! -e "$out/to_move" ] || fail "resume wrote into the farm's old folder"
# Symlinks planted in a farm folder are not written through: a logs folder elsewhere is refused, a chunk folder
# elsewhere makes its task fail without writing there.
cp -r "$farm" "$out/linked"
mkdir "$out/elsewhere" "$out/elsewhere_chunk"
echo keep > "$out/elsewhere/task_0001.log"
rm -r "$out/linked/logs" "$out/linked/chunks/0001"
ln -s "$out/elsewhere" "$out/linked/logs"
ln -s "$out/elsewhere_chunk" "$out/linked/chunks/0001"
expect_exit 2 "symlink" "$exe" farm resume "$out/linked"
[ "$(cat "$out/elsewhere/task_0001.log")" = keep ] || fail "resume wrote through a symlinked logs folder"
rm "$out/linked/logs" && mkdir "$out/linked/logs"
"$exe" farm resume "$out/linked" > "$out/linked.txt" 2>&1 && fail "a task wrote into a symlinked chunk folder"
grep -q "is a symlink" "$out/linked/logs/task_0001.log" || { cat "$out/linked/logs/task_0001.log" >&2; fail "no symlink message"; }
[ -z "$(ls -A "$out/elsewhere_chunk")" ] || fail "a task wrote through a symlinked chunk folder"
echo "moved farm, planted symlinks at $((SECONDS - t0)) s"

# A SIGKILLed pool: its tasks die with it (PR_SET_PDEATHSIG), resume runs each unfinished chunk once.
killed=$out/killed
"$exe" farm submit "$log" --frames 1-12 --chunk 2 --out "$killed" --engine local --max-parallel 2 "${size[@]}" \
  > "$killed.txt" 2>&1 &
pool=$!
for _ in $(seq 600); do  # until both tasks of the pool run (their process ids are in farm.json)
  [ "$(jq '[.jobs[].task_pids[]] | length' "$killed/farm.json" 2>/dev/null || echo 0)" = 2 ] && break
  sleep 0.05
done
[ "$(jq '[.jobs[].task_pids[]] | length' "$killed/farm.json")" = 2 ] || fail "the pool did not start 2 tasks"
kill -9 "$pool"
wait "$pool" 2>/dev/null || true
in_farm() {  # processes whose working folder is $1
  local p n=0
  for p in /proc/[0-9]*; do [ "$(readlink "$p/cwd" 2>/dev/null)" = "$1" ] && n=$((n + 1)); done
  echo $n
}
for _ in $(seq 100); do [ "$(in_farm "$killed")" = 0 ] && break; sleep 0.05; done
[ "$(in_farm "$killed")" = 0 ] || fail "the killed pool's tasks still run"
"$exe" farm resume "$killed" > "$out/killed_resume.txt" 2>&1 ||
  { cat "$out/killed_resume.txt" >&2; fail "resume after the killed pool failed"; }
assembled "$killed" || fail "not assembled after resuming the killed pool"
for k in 0 1 2 3 4 5; do
  l=$killed/logs/task_000$k.log
  [ "$(grep -c "^farm: task $k start" "$l")" = 1 ] && [ "$(grep -c "^farm: task $k exit 0" "$l")" = 1 ] ||
    { cat "$l" >&2; fail "task $k did not run exactly once to the end"; }
done
for f in "$farm"/frame_00*.png; do
  cmp -s "$f" "$killed/$(basename "$f")" || fail "the resumed killed farm's $(basename "$f") differs"
done

# A task a killed pool left running (frozen here so it cannot finish first): resume stops it before running.
rm "$killed/chunks/0000/chunk.json"
(cd "$killed" && SLURM_ARRAY_TASK_ID=0 exec setsid bash ./farm_task.sh > /dev/null 2>&1) &
stale=$!
for _ in $(seq 500); do  # until it is the job script (past setsid's own exec), leading its own group
  [ "$(tr '\0' ' ' < "/proc/$stale/cmdline" 2>/dev/null)" = "bash ./farm_task.sh " ] && break
  sleep 0.01
done
kill -STOP -- "-$stale" || fail "the stale task's process group did not start"
jq ".jobs[-1].pool_pid = 4194304 | .jobs[-1].task_pids = [[0, $stale]]" "$killed/farm.json" > "$out/stale.json"
mv "$out/stale.json" "$killed/farm.json"
"$exe" farm resume "$killed" > "$out/stale_resume.txt" 2>&1 ||
  { cat "$out/stale_resume.txt" >&2; fail "resume with a stale task failed"; }
grep -q "stopped [1-9][0-9]* processes" "$out/stale_resume.txt" ||
  { cat "$out/stale_resume.txt" >&2; fail "resume did not stop the stale task"; }
{ wait "$stale"; } 2> /dev/null || true
kill -0 "$stale" 2>/dev/null && fail "the stale task still runs"
assembled "$killed" || fail "not assembled after stopping the stale task"
echo "killed pool at $((SECONDS - t0)) s"

# The log edited after submission (last: every farm here replays it): status says so and is not assembled,
# assemble and resume refuse it.
sed -i 's/"velocity":\[0.5,0,0\]/"velocity":[0.7,0,0]/' "$log"
status_of "$farm" | jq -e '.assembled == false and (.log_changed | test("changed since submission"))' > /dev/null ||
  fail "status does not say the log changed, or says assembled"
expect_exit 2 "changed since submission" "$exe" farm assemble "$farm"
expect_exit 2 "changed since submission" "$exe" farm resume "$farm"

# A batch: a tampered report is not a finished run, and a log edited after submission is refused by status and
# assemble, as for frames.
mkdir -p "$out/library"
printf '%s\n' '{"cmd":"scene.primitive","kind":"box","name":"crate"}' > "$out/library/one.jsonl"
printf '%s\n' '{"cmd":"scene.primitive","kind":"sphere","name":"ball"}' > "$out/library/two.jsonl"
"$exe" farm batch "$out/library" --out "$out/batch" --engine local > "$out/batch.txt" 2>&1 ||
  { cat "$out/batch.txt" >&2; fail "the batch failed"; }
assembled "$out/batch" || fail "the batch is not assembled"
cp "$out/batch/runs/one/report.json" "$out/one_report.json"
echo '{}' > "$out/batch/runs/one/report.json"
status_of "$out/batch" | jq -e '.assembled == false' > /dev/null || fail "a tampered batch report counts as a run"
cp "$out/one_report.json" "$out/batch/runs/one/report.json"
assembled "$out/batch" || fail "the batch with its report restored is not assembled"
echo '{"cmd":"scene.primitive","kind":"teapot","name":"pot"}' >> "$out/library/two.jsonl"
status_of "$out/batch" | jq -e '.assembled == false and (.log_changed | test("changed since submission"))' \
  > /dev/null || fail "status does not say a batch log changed, or says assembled"
expect_exit 2 "changed since submission" "$exe" farm assemble "$out/batch"
echo "batch at $((SECONDS - t0)) s"

echo "PASS farm.hostile in $((SECONDS - t0)) s"
