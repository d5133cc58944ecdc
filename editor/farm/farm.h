// trispline::editor farm — long recordings and batch replays as array jobs: `trispline farm submit|batch|status|
// resume|assemble|task` (docs/farm.md runs it on a cluster; docs/decisions.md says why it is shaped so).
//
//   FarmPlan            what was asked (DIR/farm.json, editor/farm/farm_plan.h): the log(s), the frame range cut into
//                       chunks, the engine; checked whenever it is read
//   write_job_scripts   DIR/farm_task.sh (one array task = one chunk or one log) and DIR/farm_assemble.sh
//   farm_task           one task: the log's CRC-32 checked, the replay, the chunk's record (chunk.json)
//   farm_submit         writes the plan and the scripts, then runs them: Slurm (sbatch --array, afterok/afterany)
//                       or the local pool
//   farm_status         per task done / running / pending / failed and the frames missing, from the task logs,
//                       the chunks checked against their records and squeue / the local pool's lock
//   farm_resume         resubmits only the tasks whose output is not complete (stale tasks of a killed pool stopped)
//   farm_assemble       checks every chunk and the log, links the frames into DIR, writes animation.glb (+ MP4),
//                       report.json; for a batch, DIR/summary.json of every log's report.json
//
// Folder DIR (no path of DIR is stored in it: a copied or moved farm runs where it is; the executable and the logs
// are the absolute paths, inputs on the shared filesystem):
//   farm.json                  the plan and the submitted jobs
//   farm_task.sh               run with SLURM_ARRAY_TASK_ID=k in DIR: `trispline farm task . k`; prints a
//                              "farm: task k start T" and a "farm: task k exit STATUS end T" line around it
//   farm_assemble.sh           `trispline farm assemble .` in DIR
//   logs/task_NNNN.log         each task's output (the journal: status reads it); logs/assemble.log;
//                              logs/pool.lock (held by a running local pool)
//   chunks/NNNN/               a chunk's replay output: frame_NNNN.png|exr (written under a temporary name, then
//                              renamed), animation.piece, report.json, and chunk.json (every file's size and CRC-32,
//                              written last by the task)
//   frame_NNNN.png|exr, animation.glb, animation.mp4, report.json   after assembly: the same files as one
//                              `trispline replay LOG --frames A-B` (frames byte for byte, animation.glb too)
//   runs/NAME/, summary.json   a batch: one replay folder per log, and every report.json collected
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "editor/farm/farm_plan.h"

namespace trispline::editor {

// Writes `text` to path + ".tmp", then renames it over `path` (a reader never sees a partial file). Throws
// std::runtime_error naming the file when it cannot be written.
void write_file_atomically(const std::filesystem::path& path, const std::string& text, bool executable = false);

// A folder of its own under the system's temporary folder, removed with everything in it when the object goes: where
// the files a log writes (volume.export) go when the farm replays it only to check its range or to pose frames.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The plan stored in DIR/farm.json, checked (parse_farm_plan), its dir the absolute DIR. Throws FarmPlanError naming
// the key when it is not a usable plan, std::runtime_error when DIR holds no farm.json or it cannot be read.
FarmPlan read_plan(const std::filesystem::path& dir);
// read_plan for a farm subcommand: a plan that cannot be read is reported on `err` as "<who>: <why>" and gives
// std::nullopt (the subcommand then exits with 2).
std::optional<FarmPlan> read_plan_or_report(const std::filesystem::path& dir, std::ostream& err, const char* who);
// Writes DIR/farm.json (temporary file, then renamed). Throws std::runtime_error when it cannot be written.
void write_plan(const FarmPlan& plan);

// One task per *.jsonl file directly in `folder`, sorted by name, each with its log's CRC-32 and size. Throws
// std::invalid_argument when the folder does not exist, holds no log or more than kFarmMaxBatchLogs.
std::vector<FarmTask> plan_batch(const std::filesystem::path& folder);

// Writes DIR/farm_task.sh and DIR/farm_assemble.sh (executable, #SBATCH headers for Slurm; the local pool runs the
// same scripts) and creates DIR/logs. The scripts hold no path of the farm folder: they run in it (Slurm: sbatch
// --chdir; by hand or by the pool: the script's own folder). Every value in a shell line is single-quoted; the
// #SBATCH values are checked (check_sbatch_value). Throws std::runtime_error when they cannot be written.
void write_job_scripts(const FarmPlan& plan);

// A file's size and CRC-32 (zlib), as a task records them when it finishes and status / assemble check them.
struct FileSum {
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;
  bool operator==(const FileSum& o) const { return bytes == o.bytes && crc32 == o.crc32; }
};
// Sum of the regular file at `path`, at most `max_bytes` long; nullopt when it is missing, not a regular file (a
// symlink unless `follow_symlink`: a farm reads only its own files in its folder), longer, or unreadable.
std::optional<FileSum> file_sum(const std::filesystem::path& path, std::uint64_t max_bytes,
                                bool follow_symlink = false);
// "" when the log at `log` still has the size and CRC-32 it had at submission, else why not (named by path).
std::string log_change(const std::filesystem::path& log, std::uint32_t crc32, std::uint64_t bytes);
// A batch: "" when every task's log still has the size and CRC-32 it had at submission, else the first change and
// how many logs changed.
std::string batch_logs_changed(const FarmPlan& plan);
// A batch task's runs/<name>/report.json is a replay's report: a JSON object (at most 64 MiB) with a boolean "ok".
bool batch_report_valid(const FarmPlan& plan, const FarmTask& task);

// What the task recorded in chunks/NNNN/chunk.json when it finished, checked against the files.
struct ChunkCheck {
  bool done = false;            // every frame and the piece match the record (and decode)
  std::vector<int> bad_frames;  // frames missing, not matching the record, or not decoding at the plan's size
  std::string problem;          // why not done ("" when done)
};
// Records every frame's and the piece's size and CRC-32 in chunks/NNNN/chunk.json (written last, renamed into
// place). Throws std::runtime_error when a frame or the piece is missing or the record cannot be written.
void seal_chunk(const FarmPlan& plan, const FarmTask& task);
// Checks chunks/NNNN against its chunk.json: the frames of the task's range, each the recorded size and CRC-32 and an
// image of frame_width × frame_height (OpenImageIO: the header, and every pixel when `decode_pixels`), and the
// piece's size and CRC-32. Reads at most the chunk's files; never throws.
ChunkCheck check_chunk(const FarmPlan& plan, const FarmTask& task, bool decode_pixels);

// `trispline farm task DIR K` (what farm_task.sh runs): checks the plan and the log's CRC-32, replays task K
// (frames: `replay LOG --frames a-b --out chunks/NNNN --no-render --piece-base A`, then seal_chunk; batch: `replay
// LOG --out runs/NAME`). Returns replay's exit code, 2 when the plan, K or the log is refused.
int farm_task(const std::filesystem::path& dir, int index, std::ostream& out, std::ostream& err);

// What farm_status finds for one task.
struct FarmTaskState {
  int index = 0;
  std::string state;                // "done" | "running" | "pending" | "failed" | "missing" (never ran or output gone)
  int exit_status = -1;             // from the task log; −1 when it has not ended
  double start_s = 0, end_s = 0;    // epoch seconds from the task log (0 = none)
  std::vector<int> missing_frames;  // frames: the chunk's frames missing or not matching its record
  std::string problem;              // frames: why the chunk is not done (check_chunk), "" when it is
};

struct FarmStatus {
  std::vector<FarmTaskState> tasks;
  bool assembled = false;   // frames: every task done, the log unchanged, DIR/report.json's animation.glb and every
                            // frame in DIR matching; batch: summary.json
  std::string log_changed;  // why the log (frames) is not the one submitted; "" when unchanged
  nlohmann::json to_json() const;
};

// Reads the task logs (at most their first and last 64 KiB), checks each chunk against its record (check_chunk,
// headers only), asks squeue (one call) or the local pool's lock what still runs. Bounded by the plan's limits.
// Throws FarmPlanError / std::runtime_error when DIR holds no usable plan.
FarmStatus farm_status(const std::filesystem::path& dir);

// The tasks whose output is not complete and that are not queued or running: what farm_resume resubmits.
std::vector<int> tasks_to_resume(const FarmStatus& status);

// Records the log's size and CRC-32, replays it (its exports into a ScratchFolder) to check the range against its
// timeline, checks the plan (check_farm_plan), writes DIR/farm.json and the scripts, submits.
// Returns the exit code: 0 submitted (local: every task and the assembly succeeded), 1 a task or the assembly
// failed (local), 2 bad input (nothing submitted), 3 sbatch refused or a file could not be written (the plan, once
// written, stays for `farm resume`). Messages go to `out` / `err`; never throws.
int farm_submit(FarmPlan plan, std::ostream& out, std::ostream& err);

// Resubmits the tasks tasks_to_resume finds (and the assembly) with the plan's engine. Exit codes as farm_submit;
// 0 with a message when nothing is missing (the assembly is redone when it is out of date).
int farm_resume(const std::filesystem::path& dir, std::ostream& out, std::ostream& err);

// The assemble step (farm_assemble.sh). Frames: removes DIR/report.json (so a failed assembly is never taken for a
// finished one), refuses a log whose size or CRC-32 changed since submission and any chunk that does not match its
// record or whose frames do not decode (exit 2, nothing written), links the frames into DIR (a copy where hard links
// are not supported), joins the pieces (or replays the log and poses every frame) into DIR/animation.glb (the bytes
// one process writes), makes DIR/animation.mp4 when ffmpeg is on PATH (png), writes DIR/report.json with
// animation.glb's CRC-32. Batch: DIR/summary.json from every runs/NAME/report.json. Returns 0, 2 when the plan, the
// log or an output is refused, 3 when a file cannot be written.
int farm_assemble(const std::filesystem::path& dir, std::ostream& out, std::ostream& err);

// "trispline farm status" as text.
void print_farm_status(const FarmPlan& plan, const FarmStatus& status, std::ostream& out);

// Engines (farm_slurm.cpp, farm_local.cpp). Both run DIR/farm_task.sh for `tasks` and then DIR/farm_assemble.sh.
// Slurm: sbatch --chdir=DIR --array=LIST%max_parallel, then sbatch --dependency=afterok (frames) or afterany (batch)
// for the assembly; returns the job, throws std::runtime_error when sbatch is missing or refuses (its message quoted).
FarmJob submit_slurm(const FarmPlan& plan, const std::vector<int>& tasks);
// Local: a pool of at most max_parallel processes (nproc when 0) on this machine, in the foreground, holding
// DIR/logs/pool.lock, then the assembly when every task succeeded (frames) or always (batch). Each task's script runs
// in DIR in a process group of its own and dies with the pool (PR_SET_PDEATHSIG; `farm task` does the same with its
// script); it gets SLURM_ARRAY_TASK_ID and SLURM_CPUS_PER_TASK = CPUs / max_parallel (its llvmpipe threads), as
// under Slurm. Returns 0 when all succeeded, 1 otherwise; throws std::runtime_error when a process cannot be started
// or another pool holds the lock. `on_change` is called with the pool's job record when it starts and whenever a
// task's process starts or ends (the caller stores it in the plan).
int run_local(const FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out,
              const std::function<void(const FarmJob&)>& on_change);
// True when a local pool runs in DIR (it holds DIR/logs/pool.lock).
bool local_pool_running(const std::filesystem::path& dir);
// Stops (SIGKILL) the processes of the plan's local jobs that still run without their pool: members of a recorded
// task's process group whose working folder is DIR and whose command line is the job script or `farm task`
// (/proc/PID/cmdline and cwd: a recycled process id is never ours). Returns how many were stopped.
int stop_stale_local_tasks(const FarmPlan& plan);
// Slurm jobs and array tasks still queued or running whose working folder is plan.dir (a copy's or the original's
// jobs are not this folder's), as squeue prints their ids ("123_4", "124"); empty when squeue is missing. One call.
std::vector<std::string> slurm_active_jobs(const FarmPlan& plan);
// scancel of a job that is still queued (best effort: nothing happens when it has ended or scancel is missing).
void cancel_slurm_job(const std::string& id);

}  // namespace trispline::editor
