// The job scripts of a farm (farm_task.sh, farm_assemble.sh) and farm.json on disk. The scripts hold no path of the
// farm folder: they run in it, so a copied or moved farm runs where it is. Values in shell lines are single-quoted;
// values in #SBATCH lines (not shell-parsed: nothing can be quoted there) are checked, and refused, before writing.
#include <stdlib.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "editor/farm/farm.h"

namespace trispline::editor {
namespace fs = std::filesystem;

namespace {

// A word for bash: single-quoted, a single quote as '\''. Inside single quotes every byte but ' is literal, a
// newline included.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The #SBATCH lines both scripts share; `log` is relative to the farm folder (the job's working folder).
std::string sbatch_header(const FarmPlan& plan, const std::string& name, const std::string& log) {
  for (const auto& [option, value] : {std::pair<std::string, std::string>{"--partition", plan.partition},
                                      std::pair<std::string, std::string>{"--time", plan.time_limit}})
    if (const std::string bad = check_sbatch_value(option, value); !bad.empty()) throw std::invalid_argument(bad);
  std::string h = "#SBATCH --job-name=" + name + "\n#SBATCH --output=" + log + "\n";
  if (!plan.partition.empty()) h += "#SBATCH --partition=" + plan.partition + "\n";
  if (!plan.time_limit.empty()) h += "#SBATCH --time=" + plan.time_limit + "\n";
  return h + "#SBATCH --cpus-per-task=1\n";
}

// Into the farm folder: Slurm starts the job there (sbatch --chdir) and runs a copy of the script from its spool;
// run by hand or by the local pool, the script's own folder is the farm folder.
const char* kEnterFarm =
    "if [ -f \"$(dirname -- \"$0\")/farm.json\" ]; then cd -- \"$(dirname -- \"$0\")\" || exit 2; fi\n"
    "[ -f farm.json ] || { echo \"farm: $(pwd) holds no farm.json: run this script in its farm folder\" >&2; exit 2; "
    "}\n";

std::string task_script(const FarmPlan& plan) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# trispline farm: one array task (SLURM_ARRAY_TASK_ID); written by `trispline farm "
    << (plan.kind == "batch" ? "batch" : "submit") << "`. Paths are relative to the farm folder.\n"
    << sbatch_header(plan, "trispline-farm", "logs/task_%4a.log") << "set -u\n"
    << kEnterFarm << "task=${SLURM_ARRAY_TASK_ID:?run by sbatch --array or by trispline farm --engine local}\n"
    << "case $task in '' | *[!0-9]*) echo \"farm: SLURM_ARRAY_TASK_ID is not a task number\" >&2; exit 2 ;; esac\n"
    << "# llvmpipe draws with the CPUs the task was given, not every CPU of the node\n"
    << "export LP_NUM_THREADS=${LP_NUM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}\n"
    << "echo \"farm: task $task start $(date +%s.%N) on $(hostname)\"\n"
    << shell_quote(plan.trispline.string()) << " farm task . \"$task\"\n"
    << "status=$?\n"
    << "echo \"farm: task $task exit $status end $(date +%s.%N)\"\n"
    << "exit $status\n";
  return s.str();
}

std::string assemble_script(const FarmPlan& plan) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# trispline farm: the assemble step, after every task. Paths are relative to the farm folder.\n"
    << sbatch_header(plan, "trispline-farm-assemble", "logs/assemble.log") << kEnterFarm << "exec "
    << shell_quote(plan.trispline.string()) << " farm assemble .\n";
  return s.str();
}

}  // namespace

ScratchFolder::ScratchFolder() {
  std::string pattern = (fs::temp_directory_path() / "trispline-farm-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder in " + pattern);
  path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_file_atomically(const fs::path& path, const std::string& text, bool executable) {
  const fs::path tmp = path.string() + ".tmp";
  fs::remove(tmp);  // a file or a symlink left there is replaced, never written through
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  if (executable)
    fs::permissions(tmp, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
  fs::rename(tmp, path);
}

std::optional<FarmPlan> read_plan_or_report(const fs::path& dir, std::ostream& err, const char* who) {
  try {
    return read_plan(dir);
  } catch (const std::exception& e) {
    err << who << ": " << e.what() << "\n";
    return std::nullopt;
  }
}

FarmPlan read_plan(const fs::path& dir_in) {
  const fs::path dir = fs::absolute(dir_in).lexically_normal();
  const fs::path path = dir / "farm.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::runtime_error("no farm in '" + dir.string() + "' (" + path.string() + " is missing)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > kFarmMaxPlanBytes)
    throw FarmPlanError(
        "", "is " + std::to_string(size) + " bytes, at most " + std::to_string(kFarmMaxPlanBytes) + " allowed");
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(size)))
    throw std::runtime_error("cannot read " + path.string());
  return parse_farm_plan(text, dir.filename().empty() ? dir.parent_path() : dir);
}

void write_plan(const FarmPlan& plan) {
  FarmPlan kept = plan;
  if (kept.jobs.size() > static_cast<std::size_t>(kFarmMaxJobs))  // the oldest records go first
    kept.jobs.erase(kept.jobs.begin(), kept.jobs.end() - kFarmMaxJobs);
  write_file_atomically(plan.dir / "farm.json", kept.to_json().dump(2) + "\n");
}

void write_job_scripts(const FarmPlan& plan) {
  const std::string task = task_script(plan), assemble = assemble_script(plan);  // may refuse a value
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(plan.dir / "logs", ec)))
    throw std::invalid_argument((plan.dir / "logs").string() +
                                " is a symlink: the task logs are written only inside the farm folder");
  fs::create_directories(plan.dir / "logs");
  write_file_atomically(plan.dir / "farm_task.sh", task, true);
  write_file_atomically(plan.dir / "farm_assemble.sh", assemble, true);
}

std::vector<FarmTask> plan_batch(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw std::invalid_argument("no folder '" + folder.string() + "'");
  std::vector<fs::path> logs;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.is_regular_file() && e.path().extension() == ".jsonl") logs.push_back(fs::absolute(e.path()));
  if (logs.empty()) throw std::invalid_argument("'" + folder.string() + "' holds no command log (*.jsonl)");
  if (logs.size() > static_cast<std::size_t>(kFarmMaxBatchLogs))
    throw std::invalid_argument("'" + folder.string() + "' holds " + std::to_string(logs.size()) + " logs, at most " +
                                std::to_string(kFarmMaxBatchLogs) + " in one batch");
  std::sort(logs.begin(), logs.end());
  std::vector<FarmTask> tasks;
  std::set<std::string> names;
  for (const fs::path& log : logs) {
    FarmTask t;
    t.index = static_cast<int>(tasks.size());
    t.log = log;
    const std::optional<FileSum> sum = file_sum(log, kFarmMaxLogBytes, true);
    if (!sum) throw std::invalid_argument("cannot read the log '" + log.string() + "' (or it is over 1 GiB)");
    t.log_crc32 = sum->crc32;
    t.log_bytes = sum->bytes;
    for (const char c : log.string())
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
        throw std::invalid_argument("the log '" + log.string() + "' has a control character in its path: rename it");
    t.name = log.stem().string();
    for (int k = 2; names.count(t.name); ++k) t.name = log.stem().string() + "_" + std::to_string(k);
    names.insert(t.name);
    tasks.push_back(t);
  }
  return tasks;
}

}  // namespace trispline::editor
