// The local engine of `trispline farm`: the job scripts Slurm would run, run by a pool of processes on this machine
// in the foreground (no daemon). Each task gets SLURM_ARRAY_TASK_ID as an array task would and writes the same log.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <map>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "editor/farm.h"
#include "editor/process.h"

extern char** environ;

namespace trispline::editor {
namespace {

// Starts `bash script` with SLURM_ARRAY_TASK_ID=task (when task ≥ 0) and SLURM_CPUS_PER_TASK=cpus as Slurm would
// set them (the script gives llvmpipe that many threads), output into `log`; returns the pid.
pid_t spawn_script(const std::filesystem::path& script, int task, int cpus, const std::filesystem::path& log) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("SLURM_", 0) != 0) env.emplace_back(*e);
  if (task >= 0) env.push_back("SLURM_ARRAY_TASK_ID=" + std::to_string(task));
  env.push_back("SLURM_CPUS_PER_TASK=" + std::to_string(cpus));
  return start_process({"/bin/bash", script.string()}, log, &env);
}

std::string log_name(int task) { return "task_" + farm_task_name(task) + ".log"; }

}  // namespace

int run_local(const FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out,
              const std::function<void(const FarmJob&)>& on_start) {
  const int cpus = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int slots = plan.max_parallel > 0 ? plan.max_parallel : cpus;
  FarmJob job;
  job.engine = "local";
  job.pool_pid = static_cast<long>(::getpid());
  job.tasks = tasks;
  if (on_start) on_start(job);
  const std::filesystem::path script = plan.dir / "farm_task.sh", logs = plan.dir / "logs";
  std::map<pid_t, int> running;  // pid → task
  std::size_t next = 0;
  int failed = 0;
  while (next < tasks.size() || !running.empty()) {
    while (next < tasks.size() && static_cast<int>(running.size()) < slots) {
      const int task = tasks[next++];
      running[spawn_script(script, task, std::max(1, cpus / slots), logs / log_name(task))] = task;
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("waiting for the pool's tasks failed");
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const int code = exit_status(status);
    if (code != 0) {
      ++failed;
      out << "task " << it->second << " failed (exit " << code << "): " << (logs / log_name(it->second)).string()
          << "\n";
    } else {
      out << "task " << it->second << " done\n";
    }
    running.erase(it);
  }
  // A failed chunk leaves the frames to the assembly incomplete (afterok); a batch summarises whatever ran (afterany).
  if (failed && plan.kind != "batch") {
    out << failed << " of " << tasks.size() << " tasks failed: not assembled (trispline farm resume "
        << plan.dir.string() << " reruns them)\n";
    return 1;
  }
  const std::filesystem::path assemble_log = logs / "assemble.log";
  const int code = wait_process(spawn_script(plan.dir / "farm_assemble.sh", -1, cpus, assemble_log));
  out << (code == 0 ? "assembled: " : "assembly failed: see ") << assemble_log.string() << "\n";
  return code == 0 && failed == 0 ? 0 : 1;
}

}  // namespace trispline::editor
