// The Slurm engine of `trispline farm`: sbatch of the array job and of the assembly depending on it, squeue and
// scancel. Only Slurm's client commands are needed on the submitting machine (Debian: slurm-client).
#include <sstream>
#include <stdexcept>

#include "editor/farm.h"
#include "editor/process.h"
#include "editor/record.h"

namespace trispline::editor {
namespace {

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
  job.array_id = sbatch({"--array=" + list, (plan.dir / "farm_task.sh").string()}, "array job");
  const std::string dependency = plan.kind == "batch" ? "afterany" : "afterok";
  job.assemble_id = sbatch(
      {"--dependency=" + dependency + ":" + job.array_id, (plan.dir / "farm_assemble.sh").string()}, "assemble job");
  return job;
}

std::vector<std::string> slurm_active_tasks(const FarmJob& job) {
  if (job.array_id.empty() || find_on_path("squeue").empty()) return {};
  // --array lists every task of the array on its own line ("123_4"), pending ones included.
  const ProcessOutput c =
      run_process_output({"squeue", "--noheader", "--array", "--jobs=" + job.array_id, "--format=%i"});
  std::vector<std::string> ids;
  if (c.status != 0) return ids;  // the job has left the queue (squeue: "Invalid job id specified")
  std::istringstream lines(c.text);
  std::string line;
  while (std::getline(lines, line))
    if (!trimmed(line).empty()) ids.push_back(trimmed(line));
  return ids;
}

void cancel_slurm_job(const std::string& id) {
  if (!id.empty() && !find_on_path("scancel").empty()) run_process_output({"scancel", "--state=PENDING", id});
}

}  // namespace trispline::editor
