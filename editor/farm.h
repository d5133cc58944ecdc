// trispline::editor farm — long recordings and batch replays as array jobs: `trispline farm submit|batch|status|
// resume|assemble` (docs/farm.md runs it on a cluster; docs/decisions.md says why it is shaped so).
//
//   FarmPlan            what was asked (DIR/farm.json): the log(s), the frame range cut into chunks, the engine
//   plan_frames         a frame range cut into chunks of `chunk` frames (tasks 0..n−1)
//   write_job_scripts   DIR/farm_task.sh (one array task = one chunk or one log) and DIR/farm_assemble.sh
//   farm_submit         writes the plan and the scripts, then runs them: Slurm (sbatch --array, afterok/afterany)
//                       or the local pool
//   farm_status         per task done / running / pending / failed and the frames missing, from the task logs,
//                       the frame files and squeue
//   farm_resume         resubmits only the tasks whose output is missing
//   farm_assemble       checks every frame, links the frames into DIR, writes animation.glb (+ MP4), report.json;
//                       for a batch, DIR/summary.json of every log's report.json
//
// Folder DIR (every path in the scripts absolute, so any node of a shared filesystem can run them):
//   farm.json                  the plan and the submitted jobs
//   farm_task.sh               run with SLURM_ARRAY_TASK_ID=k: `trispline replay LOG --frames a-b --out chunks/k`
//                              (frames), or `trispline replay LOGk --out runs/NAMEk` (batch); prints a
//                              "farm: … start" and a "farm: … exit STATUS" line with epoch seconds around it
//   farm_assemble.sh           `trispline farm assemble DIR`
//   logs/task_NNNN.log         each task's output (the journal: status reads it); logs/assemble.log
//   chunks/NNNN/               a chunk's replay output: frame_NNNN.png|exr (written under a temporary name, then
//                              renamed), animation.glb of the chunk, report.json
//   frame_NNNN.png|exr, animation.glb, animation.mp4, report.json   after assembly: the same files as one
//                              `trispline replay LOG --frames A-B` (frames byte for byte, animation.glb too)
//   runs/NAME/, summary.json   a batch: one replay folder per log, and every report.json collected
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace trispline::editor {

// One array task: a chunk of frames (kind "frames") or one log (kind "batch").
struct FarmTask {
  int index = 0;
  int first = 0, last = 0;    // timeline frames, inclusive (frames)
  std::filesystem::path log;  // batch: the log this task replays
  std::string name;           // batch: its output folder's name under runs/ (the log's stem, made unique)
};

// A submitted job (Slurm job ids, or the local pool's process id) and the tasks it ran.
struct FarmJob {
  std::string engine;       // "slurm" | "local"
  std::string array_id;     // Slurm: the array job's id; local: ""
  std::string assemble_id;  // Slurm: the assemble job's id; local: ""
  long pool_pid = 0;        // local: the pool's process id while it runs
  std::vector<int> tasks;   // task indices this job ran
};

struct FarmPlan {
  std::string kind = "frames";      // "frames" | "batch"
  std::filesystem::path dir;        // absolute
  std::filesystem::path trispline;  // absolute path of the executable the scripts run
  std::filesystem::path log;        // frames: the command log (absolute)
  int frame_first = 0, frame_last = 0;
  int chunk = 0;                          // frames per task
  std::string format = "png";             // "png" | "exr"
  int width = 0, height = 0;              // pixels; 0 = the log's camera viewport
  double fps = 24;                        // the log's timeline (found at submission; the MP4's rate)
  int frame_width = 0, frame_height = 0;  // the frames' size in pixels (found at submission)
  std::string engine = "slurm";           // "slurm" | "local"
  int max_parallel = 0;                   // tasks running at once; 0 = as many as Slurm allows (local: nproc)
  std::string partition;                  // Slurm partition ("" = the cluster's default)
  std::string time_limit;                 // Slurm --time per task ("" = the partition's default)
  std::vector<FarmTask> tasks;
  std::vector<FarmJob> jobs;  // in submission order

  nlohmann::json to_json() const;
  // Throws std::runtime_error naming the field when `j` is not a plan.
  static FarmPlan from_json(const nlohmann::json& j);
};

// A task's number in folder and log names: "0007" for task 7 (chunks/0007, logs/task_0007.log).
std::string farm_task_name(int index);

// Cuts frames [first, last] into ceil((last − first + 1) / chunk) tasks of `chunk` frames (the last one shorter).
// Throws std::invalid_argument when chunk ≤ 0, first < 0 or first > last.
std::vector<FarmTask> plan_frames(int first, int last, int chunk);

// One task per *.jsonl file directly in `folder`, sorted by name. Throws std::invalid_argument when the folder does
// not exist or holds no log.
std::vector<FarmTask> plan_batch(const std::filesystem::path& folder);

// The plan stored in DIR/farm.json. Throws std::runtime_error when DIR holds no plan or it cannot be read.
FarmPlan read_plan(const std::filesystem::path& dir);
// Writes DIR/farm.json (temporary file, then renamed). Throws std::runtime_error when it cannot be written.
void write_plan(const FarmPlan& plan);

// Writes DIR/farm_task.sh and DIR/farm_assemble.sh (executable, #SBATCH headers for Slurm; the local pool runs the
// same scripts) and creates DIR/logs. Throws std::runtime_error when they cannot be written.
void write_job_scripts(const FarmPlan& plan);

// What farm_status finds for one task.
struct FarmTaskState {
  int index = 0;
  std::string state;                // "done" | "running" | "pending" | "failed" | "missing" (never ran or output gone)
  int exit_status = -1;             // from the task log; −1 when it has not ended
  double start_s = 0, end_s = 0;    // epoch seconds from the task log (0 = none)
  std::vector<int> missing_frames;  // frames: the chunk's frames not in chunks/NNNN
};

struct FarmStatus {
  std::vector<FarmTaskState> tasks;
  bool assembled = false;  // frames: every task done, DIR/animation.glb and every frame in DIR; batch: summary.json
  nlohmann::json to_json() const;
};

// Reads the task logs and output files (and squeue for a Slurm job still queued). Throws std::runtime_error when DIR
// holds no plan.
FarmStatus farm_status(const std::filesystem::path& dir);

// The tasks whose output is not complete and that are not queued or running: what farm_resume resubmits.
std::vector<int> tasks_to_resume(const FarmStatus& status);

// Replays the plan's log to check the range against its timeline, writes DIR/farm.json and the scripts, submits.
// Returns the exit code: 0 submitted (local: every task and the assembly succeeded), 1 a task or the assembly
// failed (local), 2 bad input (nothing submitted), 3 sbatch refused or a file could not be written (the plan, once
// written, stays for `farm resume`). Messages go to `out` / `err`; never throws.
int farm_submit(FarmPlan plan, std::ostream& out, std::ostream& err);

// Resubmits the tasks tasks_to_resume finds (and the assembly) with the plan's engine. Exit codes as farm_submit;
// 0 with a message when nothing is missing (the assembly is redone when it is out of date).
int farm_resume(const std::filesystem::path& dir, std::ostream& out, std::ostream& err);

// The assemble step (farm_assemble.sh). Frames: checks that every frame exists in its chunk folder (exit 2, nothing
// written, when one is missing), links them into DIR (a copy where hard links are not supported), replays the log and
// poses every frame for DIR/animation.glb (the bytes one process writes), makes DIR/animation.mp4 when ffmpeg is on
// PATH (png), writes DIR/report.json. Batch: DIR/summary.json from every runs/NAME/report.json. Returns 0, 2 when
// output is missing, 3 when a file cannot be written.
int farm_assemble(const std::filesystem::path& dir, std::ostream& out, std::ostream& err);

// "trispline farm status" as text.
void print_farm_status(const FarmPlan& plan, const FarmStatus& status, std::ostream& out);

// Engines (farm_slurm.cpp, farm_local.cpp). Both run DIR/farm_task.sh for `tasks` and then DIR/farm_assemble.sh.
// Slurm: sbatch --array=LIST%max_parallel, then sbatch --dependency=afterok (frames) or afterany (batch) for the
// assembly; returns the job, throws std::runtime_error when sbatch is missing or refuses (its message quoted).
FarmJob submit_slurm(const FarmPlan& plan, const std::vector<int>& tasks);
// Local: a pool of at most max_parallel processes (nproc when 0) on this machine, in the foreground, then the
// assembly when every task succeeded (frames) or always (batch). Each task gets SLURM_ARRAY_TASK_ID and
// SLURM_CPUS_PER_TASK = CPUs / max_parallel (its llvmpipe threads), as under Slurm. Returns 0 when all succeeded,
// 1 otherwise; throws std::runtime_error when a process cannot be started.
// `on_start` is called with the pool's job record once it runs (the caller stores it in the plan).
int run_local(const FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out,
              const std::function<void(const FarmJob&)>& on_start);
// Slurm job ids of `job`'s array still queued or running, as squeue prints them ("123_4"); empty when squeue is
// missing or the job has left the queue.
std::vector<std::string> slurm_active_tasks(const FarmJob& job);
// scancel of a job that is still queued (best effort: nothing happens when it has ended or scancel is missing).
void cancel_slurm_job(const std::string& id);

}  // namespace trispline::editor
