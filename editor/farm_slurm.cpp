// The Slurm engine of `trispline farm`: sbatch of the array job and of the assembly depending on it, squeue and
// scancel. Only Slurm's client commands are needed on the submitting machine (Debian: slurm-client).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <sstream>
#include <stdexcept>

#include "editor/farm.h"
#include "editor/record.h"

extern char** environ;

namespace trispline::editor {
namespace {

struct Captured {
  int status = -1;     // exit status; −1 when it did not run or died of a signal
  std::string output;  // stdout and stderr
};

// Runs `argv` (argv[0] a program name looked up on PATH) without a shell, stdin from /dev/null.
Captured run_capture(const std::vector<std::string>& argv) {
  Captured c;
  int fds[2];
  if (::pipe(fds) != 0) return c;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc == 0) {
    char buf[4096];
    ssize_t n = 0;
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
      if (n > 0) c.output.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (rc != 0) return c;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return c;
  c.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return c;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// sbatch --parsable prints "ID" or "ID;CLUSTER".
std::string sbatch(std::vector<std::string> args, const std::string& what) {
  args.insert(args.begin(), {"sbatch", "--parsable"});
  const Captured c = run_capture(args);
  const std::string text = trimmed(c.output);
  const std::string id = text.substr(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
  if (c.status != 0 || id.empty() || id.find_first_not_of("0123456789;") != std::string::npos)
    throw std::runtime_error("sbatch refused the " + what + " (exit " + std::to_string(c.status) + "): " + text);
  return id.substr(0, id.find(';'));
}

}  // namespace

FarmJob submit_slurm(const FarmPlan& plan, const std::vector<int>& tasks) {
  if (find_on_path("sbatch").empty())
    throw std::runtime_error("sbatch not found on PATH: install Slurm's client commands (Debian: slurm-client)");
  std::string list;
  for (int t : tasks) list += (list.empty() ? "" : ",") + std::to_string(t);
  if (plan.max_parallel > 0) list += "%" + std::to_string(plan.max_parallel);
  FarmJob job;
  job.engine = "slurm";
  job.tasks = tasks;
  job.array_id = sbatch({"--array=" + list, (plan.dir / "farm_task.sh").string()}, "array job");
  const std::string dependency = plan.kind == "batch" ? "afterany" : "afterok";
  job.assemble_id = sbatch(
      {"--dependency=" + dependency + ":" + job.array_id, (plan.dir / "farm_assemble.sh").string()}, "assemble job");
  return job;
}

std::vector<std::string> slurm_active_tasks(const FarmJob& job) {
  if (job.array_id.empty() || find_on_path("squeue").empty()) return {};
  // --array lists every task of the array on its own line ("123_4"), pending ones included.
  const Captured c = run_capture({"squeue", "--noheader", "--array", "--jobs=" + job.array_id, "--format=%i"});
  std::vector<std::string> ids;
  if (c.status != 0) return ids;  // the job has left the queue (squeue: "Invalid job id specified")
  std::istringstream lines(c.output);
  std::string line;
  while (std::getline(lines, line))
    if (!trimmed(line).empty()) ids.push_back(trimmed(line));
  return ids;
}

void cancel_slurm_job(const std::string& id) {
  if (!id.empty() && !find_on_path("scancel").empty()) run_capture({"scancel", "--state=PENDING", id});
}

}  // namespace trispline::editor
