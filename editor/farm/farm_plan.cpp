#include "editor/farm/farm_plan.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "core/commands/anim_record.h"

namespace trispline::editor {
namespace fs = std::filesystem;
using nlohmann::json;

FarmPlanError::FarmPlanError(const std::string& key, const std::string& message)
    : std::runtime_error(key.empty() ? "farm.json: " + message : "farm.json: key '" + key + "': " + message),
      key_(key) {}

namespace {

[[noreturn]] void fail(const std::string& key, const std::string& message) { throw FarmPlanError(key, message); }

const json& member(const json& j, const std::string& prefix, const char* name) {
  const auto it = j.find(name);
  if (it == j.end()) fail(prefix + name, "missing");
  return *it;
}

// An integer in [lo, hi]: a JSON integer (not 1.5, not "1", not 1e300).
long long int_value(const json& v, const std::string& key, long long lo, long long hi) {
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + v.dump().substr(0, 40));
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi))
    fail(key, "must be at most " + std::to_string(hi) + ", got " + v.dump());
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
  return x;
}

long long read_int(const json& j, const std::string& prefix, const char* name, long long lo, long long hi) {
  return int_value(member(j, prefix, name), prefix + name, lo, hi);
}

void check_text(const std::string& key, const std::string& s, std::size_t max_bytes) {
  if (s.size() > max_bytes) fail(key, "longer than " + std::to_string(max_bytes) + " bytes");
  for (const char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail(key, "holds a control character");
}

std::string read_string(const json& j, const std::string& prefix, const char* name, std::size_t max_bytes) {
  const json& v = member(j, prefix, name);
  if (!v.is_string()) fail(prefix + name, "must be a string, got " + v.dump().substr(0, 40));
  std::string s = v.get<std::string>();
  check_text(prefix + name, s, max_bytes);
  return s;
}

std::string read_choice(const json& j, const char* name, std::initializer_list<const char*> choices) {
  const std::string s = read_string(j, "", name, 16);
  for (const char* c : choices)
    if (s == c) return s;
  std::string list;
  for (const char* c : choices) list += (list.empty() ? "" : ", ") + std::string(c);
  fail(name, "must be one of " + list + ", got '" + s + "'");
}

void check_absolute(const std::string& key, const fs::path& p) {
  check_text(key, p.string(), kFarmMaxPathBytes);
  if (p.empty() || !p.is_absolute()) fail(key, "must be an absolute path, got '" + p.string() + "'");
}

// One path component naming a folder under runs/: not empty, no '/', not "." or "..".
void check_component(const std::string& key, const std::string& name) {
  check_text(key, name, 255);
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    fail(key, "must be one folder name (no '/', not '.' or '..'), got '" + name + "'");
}

const json& read_array(const json& j, const char* name, std::size_t max_size) {
  const json& v = member(j, "", name);
  if (!v.is_array()) fail(name, "must be an array");
  if (v.size() > max_size)
    fail(name, "holds " + std::to_string(v.size()) + " entries, at most " + std::to_string(max_size) + " allowed");
  return v;
}

FarmTask read_task(const json& t, const std::string& key, const std::string& kind) {
  if (!t.is_object()) fail(key, "must be an object");
  const std::string p = key + ".";
  FarmTask task;
  task.index = static_cast<int>(read_int(t, p, "index", 0, kFarmMaxFrame + 1));
  task.first = static_cast<int>(read_int(t, p, "first", 0, kFarmMaxFrame));
  task.last = static_cast<int>(read_int(t, p, "last", 0, kFarmMaxFrame));
  if (kind == "batch") {
    task.log = read_string(t, p, "log", kFarmMaxPathBytes);
    task.log_crc32 = static_cast<std::uint32_t>(read_int(t, p, "log_crc32", 0, 0xFFFFFFFFLL));
    task.log_bytes = static_cast<std::uint64_t>(read_int(t, p, "log_bytes", 0, std::numeric_limits<long long>::max()));
    task.name = read_string(t, p, "name", 255);
  }
  return task;
}

FarmJob read_job(const json& jj, const std::string& key, int task_count) {
  if (!jj.is_object()) fail(key, "must be an object");
  const std::string p = key + ".";
  FarmJob job;
  job.engine = read_string(jj, p, "engine", 16);
  job.array_id = read_string(jj, p, "array_id", 20);
  job.assemble_id = read_string(jj, p, "assemble_id", 20);
  job.pool_pid = static_cast<long>(read_int(jj, p, "pool_pid", 0, 1 << 22));
  const json& tasks = member(jj, p, "tasks");
  if (!tasks.is_array() || tasks.size() > static_cast<std::size_t>(task_count))
    fail(p + "tasks", "must be an array of at most " + std::to_string(task_count) + " task numbers");
  for (std::size_t k = 0; k < tasks.size(); ++k)
    job.tasks.push_back(
        static_cast<int>(int_value(tasks[k], p + "tasks[" + std::to_string(k) + "]", 0, task_count - 1)));
  const json& pids = member(jj, p, "task_pids");
  if (!pids.is_array() || pids.size() > static_cast<std::size_t>(task_count))
    fail(p + "task_pids", "must be an array of at most " + std::to_string(task_count) + " [task, pid] pairs");
  for (std::size_t k = 0; k < pids.size(); ++k) {
    const std::string e = p + "task_pids[" + std::to_string(k) + "]";
    if (!pids[k].is_array() || pids[k].size() != 2) fail(e, "must be a [task, pid] pair");
    job.task_pids.emplace_back(static_cast<int>(int_value(pids[k][0], e + "[0]", 0, task_count - 1)),
                               static_cast<long>(int_value(pids[k][1], e + "[1]", 1, 1 << 22)));
  }
  return job;
}

}  // namespace

std::string farm_task_name(int index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04d", index);
  return buf;
}

std::vector<FarmTask> plan_frames(int first, int last, int chunk) {
  if (chunk <= 0) throw std::invalid_argument("--chunk must be at least 1 frame, got " + std::to_string(chunk));
  if (first < 0 || first > last || last > kFarmMaxFrame)
    throw std::invalid_argument("frame range " + std::to_string(first) + "-" + std::to_string(last) +
                                " is empty, negative or past frame " + std::to_string(kFarmMaxFrame));
  std::vector<FarmTask> tasks;
  for (long a = first; a <= last; a += chunk) {
    FarmTask t;
    t.index = static_cast<int>(tasks.size());
    t.first = static_cast<int>(a);
    t.last = static_cast<int>(std::min<long>(last, a + chunk - 1));
    tasks.push_back(t);
  }
  return tasks;
}

std::string check_sbatch_value(const std::string& option, const std::string& value) {
  const char* allowed = option == "--time" ? "0123456789:-" : nullptr;
  for (const char c : value) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7F)
      return option + " holds a control character: it would end the #SBATCH line (values there cannot be quoted)";
    const bool ok = allowed ? std::string(allowed).find(c) != std::string::npos
                            : (std::isalnum(u) && u < 0x80) || c == '_' || c == '.' || c == ',' || c == '-';
    if (!ok)
      return option + " '" + value + "' holds '" + std::string(1, c) + "': an #SBATCH value here may hold only " +
             (allowed ? "digits, ':' and '-'" : "letters, digits, '_', '.', ',' and '-'");
  }
  if (value.size() > 256) return option + " is longer than 256 characters";
  return "";
}

json FarmPlan::to_json() const {
  json tasks_j = json::array();
  for (const FarmTask& t : tasks) {
    json tj = {{"index", t.index}, {"first", t.first}, {"last", t.last}};
    if (kind == "batch") {
      tj["log"] = t.log.string();
      tj["log_crc32"] = t.log_crc32;
      tj["log_bytes"] = t.log_bytes;
      tj["name"] = t.name;
    }
    tasks_j.push_back(tj);
  }
  json jobs_j = json::array();
  for (const FarmJob& job : jobs) {
    json pids = json::array();
    for (const auto& [task, pid] : job.task_pids) pids.push_back({task, pid});
    jobs_j.push_back({{"engine", job.engine},
                      {"array_id", job.array_id},
                      {"assemble_id", job.assemble_id},
                      {"pool_pid", job.pool_pid},
                      {"tasks", job.tasks},
                      {"task_pids", pids}});
  }
  return {{"version", version},
          {"kind", kind},
          {"trispline", trispline.string()},
          {"log", log.string()},
          {"log_crc32", log_crc32},
          {"log_bytes", log_bytes},
          {"frame_first", frame_first},
          {"frame_last", frame_last},
          {"chunk", chunk},
          {"format", format},
          {"width", width},
          {"height", height},
          {"fps", fps},
          {"frame_width", frame_width},
          {"frame_height", frame_height},
          {"engine", engine},
          {"max_parallel", max_parallel},
          {"partition", partition},
          {"time", time_limit},
          {"tasks", tasks_j},
          {"jobs", jobs_j}};
}

namespace {

void check_frames_plan(const FarmPlan& p) {
  check_absolute("log", p.log);
  if (p.frame_first < 0 || p.frame_first > kFarmMaxFrame)
    fail("frame_first", "must be in [0, " + std::to_string(kFarmMaxFrame) + "], got " + std::to_string(p.frame_first));
  if (p.frame_last < p.frame_first || p.frame_last > kFarmMaxFrame)
    fail("frame_last",
         "must be in [frame_first, " + std::to_string(kFarmMaxFrame) + "], got " + std::to_string(p.frame_last));
  if (p.chunk < 1 || p.chunk > kFarmMaxFrame + 1)
    fail("chunk", "must be in [1, " + std::to_string(kFarmMaxFrame + 1) + "] frames, got " + std::to_string(p.chunk));
  if ((p.width == 0) != (p.height == 0)) fail("height", "width and height are both 0 or both given");
  for (const auto& [key, size] : {std::pair{"width", p.width}, {"height", p.height}})
    if (size < 0 || size > kFarmMaxSize) fail(key, "must be 0 or in [1, 16384], got " + std::to_string(size));
  if (const std::string problem = core::frame_budget_problem(p.width, p.height); !problem.empty())
    fail("width", problem);
  for (const auto& [key, size] : {std::pair{"frame_width", p.frame_width}, {"frame_height", p.frame_height}})
    if (size < 1 || size > kFarmMaxSize) fail(key, "must be in [1, 16384], got " + std::to_string(size));
  if (const std::string problem = core::frame_budget_problem(p.frame_width, p.frame_height); !problem.empty())
    fail("frame_width", problem);
  if (!std::isfinite(p.fps) || p.fps < 0.01 || p.fps > 240) fail("fps", "must be in [0.01, 240] frames per second");
  const std::vector<FarmTask> want = plan_frames(p.frame_first, p.frame_last, p.chunk);
  if (p.tasks.size() != want.size())
    fail("tasks", "holds " + std::to_string(p.tasks.size()) + " tasks; frames " + std::to_string(p.frame_first) + "-" +
                      std::to_string(p.frame_last) + " in chunks of " + std::to_string(p.chunk) + " are " +
                      std::to_string(want.size()));
  for (std::size_t k = 0; k < want.size(); ++k) {
    const FarmTask& t = p.tasks[k];
    const std::string key = "tasks[" + std::to_string(k) + "]";
    if (t.index != want[k].index) fail(key + ".index", "must be " + std::to_string(want[k].index));
    if (t.first != want[k].first) fail(key + ".first", "must be " + std::to_string(want[k].first));
    if (t.last != want[k].last) fail(key + ".last", "must be " + std::to_string(want[k].last));
  }
}

void check_batch_plan(const FarmPlan& p) {
  if (p.tasks.empty() || p.tasks.size() > static_cast<std::size_t>(kFarmMaxBatchLogs))
    fail("tasks",
         "a batch holds 1 to " + std::to_string(kFarmMaxBatchLogs) + " logs, got " + std::to_string(p.tasks.size()));
  std::set<std::string> names;
  for (std::size_t k = 0; k < p.tasks.size(); ++k) {
    const FarmTask& t = p.tasks[k];
    const std::string key = "tasks[" + std::to_string(k) + "]";
    if (t.index != static_cast<int>(k)) fail(key + ".index", "must be " + std::to_string(k));
    if (t.first != 0 || t.last != 0) fail(key + ".first", "a batch task has no frames (0)");
    check_absolute(key + ".log", t.log);
    check_component(key + ".name", t.name);
    if (!names.insert(t.name).second) fail(key + ".name", "'" + t.name + "' is used by an earlier task");
  }
}

void check_jobs(const FarmPlan& p) {
  if (p.jobs.size() > static_cast<std::size_t>(kFarmMaxJobs))
    fail("jobs", "at most " + std::to_string(kFarmMaxJobs) + " job records, got " + std::to_string(p.jobs.size()));
  const int n = static_cast<int>(p.tasks.size());
  for (std::size_t k = 0; k < p.jobs.size(); ++k) {
    const FarmJob& job = p.jobs[k];
    const std::string key = "jobs[" + std::to_string(k) + "]";
    if (job.engine != "slurm" && job.engine != "local") fail(key + ".engine", "must be slurm or local");
    for (const auto& [name, id] : {std::pair<const char*, const std::string&>{"array_id", job.array_id},
                                   std::pair<const char*, const std::string&>{"assemble_id", job.assemble_id}})
      if (id.size() > 20 || id.find_first_not_of("0123456789") != std::string::npos)
        fail(key + "." + name, "must be a Slurm job id (digits), got '" + id + "'");
    if (job.pool_pid < 0 || job.pool_pid > (1 << 22)) fail(key + ".pool_pid", "must be a process id or 0");
    if (job.tasks.size() > p.tasks.size() || job.task_pids.size() > p.tasks.size())
      fail(key + ".tasks", "names more tasks than the plan holds");
    for (std::size_t i = 0; i < job.tasks.size(); ++i)
      if (job.tasks[i] < 0 || job.tasks[i] >= n)
        fail(key + ".tasks[" + std::to_string(i) + "]", "task " + std::to_string(job.tasks[i]) + " is not in the plan");
    for (std::size_t i = 0; i < job.task_pids.size(); ++i) {
      const auto& [t, pid] = job.task_pids[i];
      if (t < 0 || t >= n || pid < 1 || pid > (1 << 22))
        fail(key + ".task_pids[" + std::to_string(i) + "]", "is not a [task, process id] pair of this plan");
    }
  }
}

}  // namespace

void check_farm_plan(const FarmPlan& p) {
  if (p.version != kFarmPlanVersion)
    fail("version", "is " + std::to_string(p.version) + ", this trispline reads version " +
                        std::to_string(kFarmPlanVersion) + " (submit the farm again)");
  if (p.kind != "frames" && p.kind != "batch") fail("kind", "must be frames or batch, got '" + p.kind + "'");
  if (p.engine != "slurm" && p.engine != "local") fail("engine", "must be slurm or local, got '" + p.engine + "'");
  if (p.format != "png" && p.format != "exr") fail("format", "must be png or exr, got '" + p.format + "'");
  check_absolute("trispline", p.trispline);
  if (p.max_parallel < 0 || p.max_parallel > kFarmMaxParallel)
    fail("max_parallel",
         "must be in [0, " + std::to_string(kFarmMaxParallel) + "], got " + std::to_string(p.max_parallel));
  if (const std::string bad = check_sbatch_value("--partition", p.partition); !bad.empty()) fail("partition", bad);
  if (const std::string bad = check_sbatch_value("--time", p.time_limit); !bad.empty()) fail("time", bad);
  if (p.kind == "frames")
    check_frames_plan(p);
  else
    check_batch_plan(p);
  check_jobs(p);
}

FarmPlan parse_farm_plan(const std::string& text, const fs::path& dir) {
  if (text.size() > kFarmMaxPlanBytes)
    fail("", "is " + std::to_string(text.size()) + " bytes, at most " + std::to_string(kFarmMaxPlanBytes) + " allowed");
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    fail("", std::string("not JSON: ") + e.what());
  }
  if (!j.is_object()) fail("", "must hold one JSON object");
  FarmPlan p;
  p.dir = dir;
  p.version = static_cast<int>(read_int(j, "", "version", 0, 1 << 30));
  if (p.version != kFarmPlanVersion) check_farm_plan(p);  // names the version before any other key
  p.kind = read_choice(j, "kind", {"frames", "batch"});
  p.engine = read_choice(j, "engine", {"slurm", "local"});
  p.format = read_choice(j, "format", {"png", "exr"});
  p.trispline = read_string(j, "", "trispline", kFarmMaxPathBytes);
  p.log = read_string(j, "", "log", kFarmMaxPathBytes);
  p.log_crc32 = static_cast<std::uint32_t>(read_int(j, "", "log_crc32", 0, 0xFFFFFFFFLL));
  p.log_bytes = static_cast<std::uint64_t>(read_int(j, "", "log_bytes", 0, std::numeric_limits<long long>::max()));
  p.frame_first = static_cast<int>(read_int(j, "", "frame_first", 0, kFarmMaxFrame));
  p.frame_last = static_cast<int>(read_int(j, "", "frame_last", 0, kFarmMaxFrame));
  p.chunk = static_cast<int>(read_int(j, "", "chunk", p.kind == "frames" ? 1 : 0, kFarmMaxFrame + 1));
  p.width = static_cast<int>(read_int(j, "", "width", 0, kFarmMaxSize));
  p.height = static_cast<int>(read_int(j, "", "height", 0, kFarmMaxSize));
  const json& fps = member(j, "", "fps");
  if (!fps.is_number() || !std::isfinite(fps.get<double>())) fail("fps", "must be a finite number");
  p.fps = fps.get<double>();
  p.frame_width = static_cast<int>(read_int(j, "", "frame_width", 0, kFarmMaxSize));
  p.frame_height = static_cast<int>(read_int(j, "", "frame_height", 0, kFarmMaxSize));
  p.max_parallel = static_cast<int>(read_int(j, "", "max_parallel", 0, kFarmMaxParallel));
  p.partition = read_string(j, "", "partition", 256);
  p.time_limit = read_string(j, "", "time", 256);
  const json& tasks = read_array(j, "tasks", kFarmMaxFrame + 1);
  for (std::size_t k = 0; k < tasks.size(); ++k)
    p.tasks.push_back(read_task(tasks[k], "tasks[" + std::to_string(k) + "]", p.kind));
  const json& jobs = read_array(j, "jobs", kFarmMaxJobs);
  for (std::size_t k = 0; k < jobs.size(); ++k)
    p.jobs.push_back(read_job(jobs[k], "jobs[" + std::to_string(k) + "]", kFarmMaxFrame + 1));  // checked below
  check_farm_plan(p);
  return p;
}

}  // namespace trispline::editor
