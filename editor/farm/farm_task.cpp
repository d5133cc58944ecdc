// `trispline farm task DIR K`: one array task, what farm_task.sh runs. Every value comes from the checked plan,
// none from the script; the log must still be the one submitted; the task writes only under DIR/chunks/NNNN (or
// DIR/runs/NAME) and, for a chunk, records what it wrote (chunk.json) last.
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cstdlib>
#include <ostream>

#include "editor/farm/farm.h"
#include "editor/replay/replay.h"

namespace trispline::editor {
namespace fs = std::filesystem;

namespace {

// Under the local pool (TRISPLINE_FARM_POOL set) the job script leads this process group: die with it, so a killed
// pool leaves no replay running. Returns false when the script is already gone.
bool die_with_job_script() {
  if (!std::getenv("TRISPLINE_FARM_POOL")) return true;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  return ::getppid() == ::getpgrp();
}

// Creates `sub` under `dir` (each level), refusing a symlink at any level: a task writes only inside the farm.
void make_inside(const fs::path& dir, const std::vector<std::string>& sub) {
  fs::path p = dir;
  for (const std::string& s : sub) {
    p /= s;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(p, ec)))
      throw std::invalid_argument(p.string() + " is a symlink: a farm task writes only inside the farm folder");
    fs::create_directory(p);  // throws when a file is in the way
  }
}

}  // namespace

int farm_task(const fs::path& dir, int index, std::ostream& out, std::ostream& err) {
  if (!die_with_job_script()) {
    err << "farm task: the job script that started this task has ended (its pool was stopped)\n";
    return 1;
  }
  const std::optional<FarmPlan> read = read_plan_or_report(dir, err, "farm task");
  if (!read) return 2;
  const FarmPlan& plan = *read;
  if (index < 0 || index >= static_cast<int>(plan.tasks.size())) {
    err << "farm task: task " << index << " is not in the plan (tasks 0-" << plan.tasks.size() - 1 << ")\n";
    return 2;
  }
  const FarmTask& task = plan.tasks[static_cast<std::size_t>(index)];
  const bool batch = plan.kind == "batch";
  ReplayOptions o;
  o.log = batch ? task.log : plan.log;
  const std::string changed = batch ? log_change(task.log, task.log_crc32, task.log_bytes)
                                    : log_change(plan.log, plan.log_crc32, plan.log_bytes);
  if (!changed.empty()) {
    err << "farm task " << index << ": " << changed << "\n";
    return 2;
  }
  o.width = plan.width;
  o.height = plan.height;
  try {
    if (batch) {
      make_inside(plan.dir, {"runs", task.name});
      o.out_dir = plan.dir / "runs" / task.name;
    } else {
      make_inside(plan.dir, {"chunks", farm_task_name(index)});
      o.out_dir = plan.dir / "chunks" / farm_task_name(index);
      fs::remove(o.out_dir / "chunk.json");  // the record of an earlier run no longer holds
      o.render = false;
      o.frames_given = true;
      o.frames.frame_first = task.first;
      o.frames.frame_last = task.last;
      o.frames.format = plan.format;
      o.frames.piece_base = plan.frame_first;
    }
  } catch (const std::exception& e) {
    err << "farm task " << index << ": " << e.what() << "\n";
    return 3;
  }
  out << "farm task " << index << ": replay " << o.log.string() << " into " << o.out_dir.string() << "\n" << std::flush;
  int rc = 0;
  try {
    rc = run_replay(o);
    if (rc == 0 && !batch) seal_chunk(plan, task);
  } catch (const std::exception& e) {
    err << "farm task " << index << ": " << e.what() << "\n";
    return 3;
  }
  return rc;
}

}  // namespace trispline::editor
