// The local engine of `trispline farm`: the job scripts Slurm would run, run by a pool of processes on this machine
// in the foreground (no daemon). Each task gets SLURM_ARRAY_TASK_ID as an array task would and writes the same log.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "editor/farm.h"

extern char** environ;

namespace trispline::editor {
namespace {

// Starts `bash script` with SLURM_ARRAY_TASK_ID=task (when task ≥ 0), output into `log`; returns the pid.
// SLURM_CPUS_PER_TASK=cpus as Slurm would set it (the script gives llvmpipe that many threads).
pid_t spawn_script(const std::filesystem::path& script, int task, int cpus, const std::filesystem::path& log) {
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("SLURM_", 0) != 0) env_text.emplace_back(*e);
  if (task >= 0) env_text.push_back("SLURM_ARRAY_TASK_ID=" + std::to_string(task));
  env_text.push_back("SLURM_CPUS_PER_TASK=" + std::to_string(cpus));
  std::vector<char*> env;
  for (std::string& e : env_text) env.push_back(e.data());
  env.push_back(nullptr);
  std::string bash = "/bin/bash", path = script.string();
  char* argv[] = {bash.data(), path.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv, env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + path + ": " + std::strerror(rc));
  return pid;
}

int wait_status(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
  const int code = wait_status(spawn_script(plan.dir / "farm_assemble.sh", -1, cpus, assemble_log));
  out << (code == 0 ? "assembled: " : "assembly failed: see ") << assemble_log.string() << "\n";
  return code == 0 && failed == 0 ? 0 : 1;
}

}  // namespace trispline::editor
