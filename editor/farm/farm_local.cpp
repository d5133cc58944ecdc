// The local engine of `trispline farm`: the job scripts Slurm would run, run by a pool of processes on this machine
// in the foreground (no daemon). Each task gets SLURM_ARRAY_TASK_ID as an array task would and writes the same log.
// The pool holds DIR/logs/pool.lock while it runs; each task's script leads a process group of its own and dies with
// the pool (PR_SET_PDEATHSIG), and resume stops what a killed pool left (stop_stale_local_tasks).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <stdexcept>
#include <thread>

#include "editor/farm/farm.h"
#include "editor/replay/process.h"

extern char** environ;

namespace trispline::editor {
namespace fs = std::filesystem;

namespace {

// DIR/logs/pool.lock, held (flock) while the pool runs; released by the kernel when the pool dies.
class PoolLock {
 public:
  explicit PoolLock(const fs::path& dir) {
    const fs::path path = dir / "logs" / "pool.lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot open " + path.string());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw std::runtime_error("a local pool already runs in " + dir.string() + " (it holds " + path.string() + ")");
    }
  }
  ~PoolLock() { ::close(fd_); }
  PoolLock(const PoolLock&) = delete;
  PoolLock& operator=(const PoolLock&) = delete;

 private:
  int fd_ = -1;
};

// Starts `bash SCRIPT` in `dir` (script relative to it) with SLURM_ARRAY_TASK_ID=task (when task ≥ 0) and
// SLURM_CPUS_PER_TASK=cpus as Slurm would set them, output into `log` (truncated). The child leads its own process
// group and gets SIGKILL when the pool dies. Everything the child needs is built before fork (async-signal-safe
// calls only after it).
pid_t spawn_script(const fs::path& dir, const std::string& script, int task, int cpus, const fs::path& log) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("SLURM_", 0) != 0 && std::string(*e).rfind("TRISPLINE_FARM_POOL=", 0) != 0)
      env.emplace_back(*e);
  if (task >= 0) env.push_back("SLURM_ARRAY_TASK_ID=" + std::to_string(task));
  env.push_back("SLURM_CPUS_PER_TASK=" + std::to_string(cpus));
  env.push_back("TRISPLINE_FARM_POOL=" + std::to_string(::getpid()));
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::string bash = "/bin/bash", rel = "./" + script;
  char* argv[] = {bash.data(), rel.data(), nullptr};
  const std::string dir_s = dir.string(), log_s = log.string();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + script + ": fork failed");
  if (pid == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the pool died before prctl took effect
    const int out = ::open(log_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);  // never through a link
    const int in = ::open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0 || ::chdir(dir_s.c_str()) != 0) ::_exit(127);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(out, 2);
    ::execve(argv[0], argv, envp.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also from the parent: the group exists before anyone signals it
  return pid;
}

std::string log_name(int task) { return "task_" + farm_task_name(task) + ".log"; }

std::string read_small(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string s(4096, '\0');
  in.read(s.data(), static_cast<std::streamsize>(s.size()));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

// The process group of /proc/PID/stat (field 5, after the command name in parentheses); −1 when unreadable.
long process_group(const fs::path& proc) {
  const std::string stat = read_small(proc / "stat");
  const std::size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  char state = 0;
  long ppid = 0, pgrp = -1;
  return std::sscanf(stat.c_str() + close + 1, " %c %ld %ld", &state, &ppid, &pgrp) == 3 ? pgrp : -1;
}

// A process of a farm task: its job script (`/bin/bash ./farm_task.sh`) or `trispline farm task . K`.
bool is_task_command(const std::string& cmdline) {
  std::vector<std::string> args;
  for (std::size_t a = 0; a < cmdline.size();) {
    const std::size_t z = cmdline.find('\0', a);
    args.push_back(cmdline.substr(a, z == std::string::npos ? std::string::npos : z - a));
    a = z == std::string::npos ? cmdline.size() : z + 1;
  }
  if (args.size() == 2 && args[1] == "./farm_task.sh") return true;
  return args.size() == 5 && args[1] == "farm" && args[2] == "task" && args[3] == ".";
}

}  // namespace

int run_local(const FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out,
              const std::function<void(const FarmJob&)>& on_change) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(plan.dir / "logs", ec)))
    throw std::runtime_error((plan.dir / "logs").string() + " is a symlink: the pool writes only inside the farm");
  fs::create_directories(plan.dir / "logs");
  const PoolLock lock(plan.dir);
  const int cpus = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int slots = plan.max_parallel > 0 ? plan.max_parallel : cpus;
  FarmJob job;
  job.engine = "local";
  job.pool_pid = static_cast<long>(::getpid());
  job.tasks = tasks;
  if (on_change) on_change(job);
  const fs::path logs = plan.dir / "logs";
  std::map<pid_t, int> running;  // pid → task
  const auto record = [&] {
    job.task_pids.clear();
    for (const auto& [pid, task] : running) job.task_pids.emplace_back(task, static_cast<long>(pid));
    if (on_change) on_change(job);
  };
  std::size_t next = 0;
  int failed = 0;
  while (next < tasks.size() || !running.empty()) {
    bool started = false;
    while (next < tasks.size() && static_cast<int>(running.size()) < slots) {
      const int task = tasks[next++];
      running[spawn_script(plan.dir, "farm_task.sh", task, std::max(1, cpus / slots), logs / log_name(task))] = task;
      started = true;
    }
    if (started) record();
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
    record();
  }
  // A failed chunk leaves the frames to the assembly incomplete (afterok); a batch summarises whatever ran (afterany).
  if (failed && plan.kind != "batch") {
    out << failed << " of " << tasks.size() << " tasks failed: not assembled (trispline farm resume "
        << plan.dir.string() << " reruns them)\n";
    return 1;
  }
  const fs::path assemble_log = logs / "assemble.log";
  const int code = wait_process(spawn_script(plan.dir, "farm_assemble.sh", -1, cpus, assemble_log));
  out << (code == 0 ? "assembled: " : "assembly failed: see ") << assemble_log.string() << "\n";
  return code == 0 && failed == 0 ? 0 : 1;
}

bool local_pool_running(const fs::path& dir) {
  const int fd = ::open((dir / "logs" / "pool.lock").c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return held;
}

int stop_stale_local_tasks(const FarmPlan& plan) {
  std::set<long> groups;
  for (const FarmJob& job : plan.jobs)
    if (job.engine == "local")
      for (const auto& [task, pid] : job.task_pids) groups.insert(pid);
  if (groups.empty()) return 0;
  std::error_code ec;
  const fs::path dir = fs::canonical(plan.dir, ec);
  if (ec) return 0;
  // A recorded group is ours when one of its members is a task of this folder (cwd and command line): a group id is
  // not reused while the group has members, so its other members (date, hostname, the replay) are the task's too.
  std::set<long> ours;
  std::vector<std::pair<pid_t, long>> members;  // (pid, group) of every process in a recorded group
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos || name.size() > 9) continue;
    const long group = process_group(entry.path());
    if (!groups.count(group)) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name));
    members.emplace_back(pid, group);
    std::error_code ec2;
    if (fs::read_symlink(entry.path() / "cwd", ec2) == dir && !ec2 &&
        is_task_command(read_small(entry.path() / "cmdline")))
      ours.insert(group);  // another folder's (a copy's) task has another cwd
  }
  int stopped = 0;
  for (const long group : ours)
    if (::kill(static_cast<pid_t>(-group), SIGKILL) == 0)
      for (const auto& [pid, g] : members) stopped += g == group;
  for (const auto& [pid, group] : members) {  // until the kernel has removed them (SIGKILL cannot be caught)
    if (!ours.count(group)) continue;
    const std::string proc = "/proc/" + std::to_string(pid);
    for (int k = 0; k < 500 && fs::exists(proc, ec) && !read_small(proc + "/cmdline").empty(); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return stopped;
}

}  // namespace trispline::editor
