// The Slurm engine of `trispline farm`: sbatch of the array job and of the assembly depending on it, squeue and
// scancel. Only Slurm's client commands are needed on the submitting machine (Debian: slurm-client). Jobs run in the
// farm folder (--chdir, given at each submission: the scripts hold no path of it), and a job counts as this
// folder's only when squeue shows that folder as its working folder.
#include <set>
#include <sstream>
#include <stdexcept>

#include "editor/farm/farm.h"
#include "editor/replay/process.h"
#include "editor/replay/record.h"

namespace trispline::editor {
namespace {

// The farm folder as Slurm records it: absolute, symlinks resolved (as squeue's %Z prints it).
std::string farm_workdir(const std::filesystem::path& dir) {
  std::error_code ec;
  const std::filesystem::path c = std::filesystem::canonical(dir, ec);
  return (ec ? dir : c).string();
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// sbatch --parsable prints "ID" or "ID;CLUSTER".
std::string sbatch(std::vector<std::string> args, const std::string& what) {
  args.insert(args.begin(), {"sbatch", "--parsable"});
  const ProcessOutput c = run_process_output(args);
  const std::string text = trimmed(c.text);
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
  const std::string chdir = "--chdir=" + farm_workdir(plan.dir);
  job.array_id = sbatch({chdir, "--array=" + list, (plan.dir / "farm_task.sh").string()}, "array job");
  const std::string dependency = plan.kind == "batch" ? "afterany" : "afterok";
  job.assemble_id =
      sbatch({chdir, "--dependency=" + dependency + ":" + job.array_id, (plan.dir / "farm_assemble.sh").string()},
             "assemble job");
  return job;
}

std::vector<std::string> slurm_active_jobs(const FarmPlan& plan) {
  std::set<std::string> ours;  // this plan's job ids
  for (const FarmJob& job : plan.jobs)
    if (job.engine == "slurm")
      for (const std::string& id : {job.array_id, job.assemble_id})
        if (!id.empty()) ours.insert(id);
  if (ours.empty() || find_on_path("squeue").empty()) return {};
  // One call for every job: --array lists each task of an array on its own line ("123_4"), pending ones included;
  // %Z is the job's working folder.
  const ProcessOutput c = run_process_output({"squeue", "--noheader", "--me", "--array", "--format=%i %Z"});
  std::vector<std::string> ids;
  if (c.status != 0) return ids;
  const std::string dir = farm_workdir(plan.dir);
  std::istringstream lines(c.text);
  std::string line;
  while (std::getline(lines, line)) {
    line = trimmed(line);
    const std::size_t space = line.find(' ');
    if (space == std::string::npos || line.substr(space + 1) != dir) continue;
    const std::string id = line.substr(0, space);
    if (ours.count(id.substr(0, id.find('_')))) ids.push_back(id);
  }
  return ids;
}

void cancel_slurm_job(const std::string& id) {
  if (!id.empty() && !find_on_path("scancel").empty()) run_process_output({"scancel", "--state=PENDING", id});
}

}  // namespace trispline::editor
