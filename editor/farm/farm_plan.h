// trispline::editor farm plan — what DIR/farm.json holds, and its reader: a farm folder is shared input, so every
// value is checked on read (types, ranges, tasks consistent with the frames, paths that stay in the folder) before
// anything acts on it. No GL, no processes: the fuzz target fuzz_farm_json links this unit alone.
//
//   FarmTask / FarmJob / FarmPlan   one array task, one submitted job, the whole plan
//   FarmPlanError                   a bad plan; key() names the farm.json key ("chunk", "tasks[3].last")
//   parse_farm_plan                 farm.json's text → a checked plan (throws FarmPlanError, nothing else)
//   check_farm_plan                 the same checks on a plan built in memory (submit checks its plan with them)
//   plan_frames                     a frame range cut into chunks
//   check_sbatch_value              a value written into an #SBATCH line (partition, time limit)
//
// Paths in farm.json: the farm folder itself is not stored (it is where farm.json is: a copied or moved farm works
// where it is); chunk and run folders are named by task number or by a single path component (`name`). Absolute
// paths are the inputs outside the folder: the trispline executable and the command log(s), each log with the
// CRC-32 and size it had at submission.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trispline::editor {

// Bounds of a plan (checked on read and at submission).
inline constexpr int kFarmMaxFrame = 100000;            // the timeline's last frame number (anim.timeline "end")
inline constexpr int kFarmMaxBatchLogs = 10000;         // logs of one `farm batch`
inline constexpr int kFarmMaxJobs = 1000;               // job records kept (older ones are dropped)
inline constexpr int kFarmMaxParallel = 100000;         // --max-parallel
inline constexpr int kFarmMaxSize = 16384;              // --width / --height, pixels
inline constexpr std::size_t kFarmMaxPathBytes = 4096;  // a path in farm.json
inline constexpr std::uintmax_t kFarmMaxPlanBytes = 64u << 20;  // farm.json itself
inline constexpr std::uint64_t kFarmMaxLogBytes = 1ull << 30;   // a command log a farm replays
inline constexpr int kFarmPlanVersion = 2;

// A plan that cannot be used. key(): the farm.json key at fault ("" when the file as a whole is bad).
class FarmPlanError : public std::runtime_error {
 public:
  FarmPlanError(const std::string& key, const std::string& message);
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// One array task: a chunk of frames (kind "frames") or one log (kind "batch").
struct FarmTask {
  int index = 0;
  int first = 0, last = 0;      // timeline frames, inclusive (frames); 0 (batch)
  std::filesystem::path log;    // batch: the log this task replays (absolute)
  std::uint32_t log_crc32 = 0;  // batch: its CRC-32 (zlib) at submission
  std::uint64_t log_bytes = 0;  // batch: its size at submission
  std::string name;             // batch: its output folder under runs/ (one path component: the log's stem, unique)
};

// A submitted job: Slurm job ids, or the local pool's process and its tasks' process ids.
struct FarmJob {
  std::string engine;       // "slurm" | "local"
  std::string array_id;     // Slurm: the array job's id (digits); local: ""
  std::string assemble_id;  // Slurm: the assemble job's id (digits); local: ""
  long pool_pid = 0;        // local: the pool's process id while it runs (0 once it has finished)
  std::vector<int> tasks;   // task indices this job ran
  // local: (task, process id) of each task's job script, the leader of its own process group, while it runs
  std::vector<std::pair<int, long>> task_pids;
};

struct FarmPlan {
  int version = kFarmPlanVersion;
  std::string kind = "frames";            // "frames" | "batch"
  std::filesystem::path dir;              // the farm folder (absolute): where farm.json was read, never stored in it
  std::filesystem::path trispline;        // absolute path of the executable the scripts run
  std::filesystem::path log;              // frames: the command log (absolute)
  std::uint32_t log_crc32 = 0;            // frames: the log's CRC-32 (zlib) at submission: a changed log is refused
  std::uint64_t log_bytes = 0;            // frames: the log's size at submission
  int frame_first = 0, frame_last = 0;    // inclusive, in [0, kFarmMaxFrame]
  int chunk = 0;                          // frames per task, ≥ 1
  std::string format = "png";             // "png" | "exr"
  int width = 0, height = 0;              // pixels; both 0 = the log's camera viewport
  double fps = 24;                        // the log's timeline (found at submission; the MP4's rate), [0.01, 240]
  int frame_width = 0, frame_height = 0;  // the frames' size in pixels (found at submission)
  std::string engine = "slurm";           // "slurm" | "local"
  int max_parallel = 0;                   // tasks running at once; 0 = as many as Slurm allows (local: nproc)
  std::string partition;                  // Slurm partition ("" = the cluster's default)
  std::string time_limit;                 // Slurm --time per task ("" = the partition's default)
  std::vector<FarmTask> tasks;
  std::vector<FarmJob> jobs;  // in submission order, at most kFarmMaxJobs

  nlohmann::json to_json() const;
};

// The plan in `text` (farm.json's bytes), its dir set to `dir`. Throws FarmPlanError naming the key for anything
// that is not a plan this build wrote: not JSON, a missing key or a wrong type, a value out of range, tasks that
// are not the frames cut into chunks (or not one per log), a run name that is not one path component, a relative
// log or executable path, control characters in any string.
FarmPlan parse_farm_plan(const std::string& text, const std::filesystem::path& dir);

// The checks of parse_farm_plan on a plan in memory. Throws FarmPlanError naming the key.
void check_farm_plan(const FarmPlan& plan);

// "" when `value` may be written into an #SBATCH line as the value of `option` ("--partition": letters, digits and
// _ . , - only; "--time": digits, ':' and '-'), else why not (control characters, blanks, quotes: an #SBATCH line is
// not shell-parsed, so such a value cannot be quoted, only refused).
std::string check_sbatch_value(const std::string& option, const std::string& value);

// A task's number in folder and log names: "0007" for task 7 (chunks/0007, logs/task_0007.log).
std::string farm_task_name(int index);

// Cuts frames [first, last] into ceil((last − first + 1) / chunk) tasks of `chunk` frames (the last one shorter).
// Throws std::invalid_argument when chunk ≤ 0, first < 0, first > last or last > kFarmMaxFrame.
std::vector<FarmTask> plan_frames(int first, int last, int chunk);

}  // namespace trispline::editor
