// `trispline farm submit|batch|status|resume`: the plan written and submitted, what a farm folder holds now, and
// what to run again. The plan is checked whenever it is read (farm_plan.h); a chunk counts as done only when its
// files match what its task recorded (farm_verify.cpp).
#include "editor/farm/farm.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/commands/anim_record.h"
#include "editor/commands/history.h"
#include "editor/replay/record.h"
#include "editor/replay/render_scene.h"
#include "editor/replay/replay.h"

namespace trispline::editor {
namespace fs = std::filesystem;

namespace {

constexpr std::streamsize kTaskLogWindow = 64 << 10;

// The first and the last 64 KiB of a task log (the whole of a shorter one): where its "farm:" lines are.
std::string task_log_ends(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamsize size = in.tellg();
  auto read_at = [&](std::streamoff at, std::streamsize n) {
    std::string s(static_cast<std::size_t>(n), '\0');
    in.seekg(at);
    in.read(s.data(), n);
    s.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    return s;
  };
  if (size <= 2 * kTaskLogWindow) return read_at(0, size);
  return read_at(0, kTaskLogWindow) + "\n" + read_at(size - kTaskLogWindow, kTaskLogWindow);
}

// Task `st.index`'s "farm: task K start T" and "farm: task K exit S end T" lines (other tasks' lines are ignored).
void read_task_log(const fs::path& log, FarmTaskState& st) {
  std::istringstream in(task_log_ends(log));
  const std::string prefix = "farm: task " + std::to_string(st.index) + " ";
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    for (std::size_t i = 0; i + 1 < w.size() && i < 16; ++i) {
      try {
        if (w[i] == "start") st.start_s = std::stod(w[i + 1]);
        if (w[i] == "end") st.end_s = std::stod(w[i + 1]);
        if (w[i] == "exit") st.exit_status = std::stoi(w[i + 1]);
      } catch (const std::exception&) {
      }
    }
  }
}

// Replays the plan's log (no rendering) and checks the frame range against its timeline: "" when it fits.
std::string check_range(const FarmPlan& plan, core::Scene& scene) {
  History history(scene);
  const ScratchFolder scratch;  // what the log exports goes there, not next to the log
  const ReplayResult r = replay_lines(history, plan.log, {}, scratch.path());
  if (!r.ok) return "the log does not replay: " + r.error;
  const std::string err = core::frame_range_error(scene.timeline, plan.frame_first, plan.frame_last);
  return err.empty()
             ? ""
             : "--frames " + std::to_string(plan.frame_first) + "-" + std::to_string(plan.frame_last) + ": " + err;
}

// Slurm keeps a job's working folder on one line of squeue: a folder name with a control character cannot be one.
std::string slurm_folder_error(const FarmPlan& plan) {
  if (plan.engine != "slurm") return "";
  for (const char c : plan.dir.string())
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
      return "--out '" + plan.dir.string() +
             "' holds a control character: Slurm's job records (squeue) hold the "
             "farm folder on one line; rename it, or use --engine local";
  return "";
}

// Tasks a job of this folder still has queued or running: squeue, or a local pool holding the folder's lock.
std::set<int> queued_tasks(const FarmPlan& plan) {
  std::set<int> queued;
  if (local_pool_running(plan.dir))
    for (auto job = plan.jobs.rbegin(); job != plan.jobs.rend(); ++job)
      if (job->engine == "local") {
        queued.insert(job->tasks.begin(), job->tasks.end());
        break;
      }
  for (const std::string& id : slurm_active_jobs(plan)) {
    const std::size_t us = id.find('_');
    if (us == std::string::npos || id.size() - us > 7) continue;  // the assemble job, or not a task number
    const std::string digits = id.substr(us + 1);
    if (!digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos)
      queued.insert(std::stoi(digits));
  }
  return queued;
}

// Every frame in DIR and DIR/animation.glb are what the last assembly wrote (its report.json).
bool assembly_matches(const FarmPlan& plan) {
  const fs::path report_path = plan.dir / "report.json";
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(report_path, ec)) || fs::file_size(report_path, ec) > (256u << 20))
    return false;
  nlohmann::json report;
  try {
    std::ifstream in(report_path, std::ios::binary);
    report = nlohmann::json::parse(in);
    const nlohmann::json& r = report.at("record");
    const std::optional<FileSum> glb = file_sum(plan.dir / "animation.glb", 1ull << 40);
    if (!glb || r.at("glb_bytes").get<std::uint64_t>() != glb->bytes ||
        r.at("glb_crc32").get<std::uint64_t>() != glb->crc32 ||
        r.at("log_crc32").get<std::uint64_t>() != plan.log_crc32)
      return false;
  } catch (const std::exception&) {
    return false;
  }
  for (const FarmTask& t : plan.tasks)
    for (int f = t.first; f <= t.last; ++f) {
      const fs::path in_dir = plan.dir / frame_file_name(f, plan.format);
      const fs::path in_chunk = plan.dir / "chunks" / farm_task_name(t.index) / frame_file_name(f, plan.format);
      if (!fs::is_regular_file(fs::symlink_status(in_dir, ec))) return false;
      if (fs::equivalent(in_dir, in_chunk, ec)) continue;
      const std::optional<FileSum> a = file_sum(in_dir, 1ull << 40), b = file_sum(in_chunk, 1ull << 40);
      if (!a || !b || !(*a == *b)) return false;
    }
  return true;
}

// Runs `tasks` with the plan's engine, records the job in farm.json and prints what happened.
int run_engine(FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out) {
  std::string list;
  for (int t : tasks) list += (list.empty() ? "" : ",") + std::to_string(t);
  if (plan.engine == "slurm") {
    const std::vector<std::string> active = slurm_active_jobs(plan);
    for (const FarmJob& old : plan.jobs)  // an assembly still waiting on a failed array would never start
      if (old.engine == "slurm" && std::count(active.begin(), active.end(), old.assemble_id))
        cancel_slurm_job(old.assemble_id);
    FarmJob job = submit_slurm(plan, tasks);
    plan.jobs.push_back(job);
    write_plan(plan);
    out << "submitted array job " << job.array_id << " (tasks " << list << ") and assemble job " << job.assemble_id
        << " (" << (plan.kind == "batch" ? "afterany" : "afterok") << ")\n"
        << "status: trispline farm status " << plan.dir.string() << "\n";
    return 0;
  }
  out << "local pool: tasks " << list << ", at most "
      << (plan.max_parallel > 0 ? plan.max_parallel : static_cast<int>(std::thread::hardware_concurrency()))
      << " at once\n";
  bool started = false;
  const int rc = run_local(plan, tasks, out, [&](const FarmJob& job) {
    if (started)
      plan.jobs.back() = job;
    else
      plan.jobs.push_back(job);
    write_plan(plan);
    started = true;
  });
  if (started) {
    plan.jobs.back().pool_pid = 0;  // the pool has finished
    plan.jobs.back().task_pids.clear();
    write_plan(plan);
  }
  return rc;
}

}  // namespace

nlohmann::json FarmStatus::to_json() const {
  nlohmann::json tasks_j = nlohmann::json::array();
  std::map<std::string, int> counts = {{"done", 0}, {"running", 0}, {"pending", 0}, {"failed", 0}, {"missing", 0}};
  std::vector<int> missing;
  for (const FarmTaskState& t : tasks) {
    ++counts[t.state];
    missing.insert(missing.end(), t.missing_frames.begin(), t.missing_frames.end());
    tasks_j.push_back({{"index", t.index},
                       {"state", t.state},
                       {"exit", t.exit_status},
                       {"start_s", t.start_s},
                       {"end_s", t.end_s},
                       {"missing_frames", t.missing_frames},
                       {"problem", t.problem}});
  }
  nlohmann::json j = {{"tasks", tasks_j}, {"missing_frames", missing}, {"assembled", assembled}};
  j["log_changed"] = log_changed.empty() ? nlohmann::json(nullptr) : nlohmann::json(log_changed);
  for (const auto& [name, n] : counts) j[name] = n;
  return j;
}

FarmStatus farm_status(const fs::path& dir) {
  const FarmPlan plan = read_plan(dir);
  const std::set<int> queued = queued_tasks(plan);
  FarmStatus status;
  status.log_changed =
      plan.kind == "frames" ? log_change(plan.log, plan.log_crc32, plan.log_bytes) : batch_logs_changed(plan);
  std::error_code ec;
  for (const FarmTask& t : plan.tasks) {
    FarmTaskState st;
    st.index = t.index;
    read_task_log(plan.dir / "logs" / ("task_" + farm_task_name(t.index) + ".log"), st);
    bool output = true;
    if (plan.kind == "batch") {
      output = batch_report_valid(plan, t);
      if (!output && fs::exists(plan.dir / "runs" / t.name / "report.json", ec))
        st.problem = "runs/" + t.name + "/report.json is not a replay's report";
    } else {
      const ChunkCheck c = check_chunk(plan, t, false);
      output = c.done;
      st.missing_frames = c.bad_frames;
      st.problem = c.problem;
    }
    const bool ended = st.end_s > 0;
    if (queued.count(t.index))
      st.state = st.start_s > 0 && !ended ? "running" : "pending";
    else if (ended && st.exit_status != 0)
      st.state = "failed";
    else if (output)
      st.state = "done";
    else if (st.start_s > 0 && !ended)
      st.state = "failed";  // started, never ended and no longer queued: killed (time limit, node lost, pool killed)
    else
      st.state = "missing";
    status.tasks.push_back(st);
  }
  const bool all_done =
      std::all_of(status.tasks.begin(), status.tasks.end(), [](const FarmTaskState& t) { return t.state == "done"; });
  status.assembled =
      all_done && status.log_changed.empty() &&
      (plan.kind == "batch" ? fs::is_regular_file(plan.dir / "summary.json", ec) : assembly_matches(plan));
  return status;
}

std::vector<int> tasks_to_resume(const FarmStatus& status) {
  std::vector<int> out;
  for (const FarmTaskState& t : status.tasks)
    if (t.state == "failed" || t.state == "missing") out.push_back(t.index);
  return out;
}

void print_farm_status(const FarmPlan& plan, const FarmStatus& status, std::ostream& out) {
  const nlohmann::json j = status.to_json();
  out << "farm " << plan.dir.string() << ": " << plan.tasks.size() << " tasks, engine " << plan.engine;
  if (plan.kind == "batch")
    out << ", batch of logs\n";
  else
    out << ", frames " << plan.frame_first << "-" << plan.frame_last << " in chunks of " << plan.chunk << "\n";
  for (const FarmJob& job : plan.jobs)
    if (job.engine == "slurm") out << "  job " << job.array_id << " (assemble " << job.assemble_id << ")\n";
  if (!status.log_changed.empty()) out << "  " << status.log_changed << "\n";
  out << "  done " << j["done"] << ", running " << j["running"] << ", pending " << j["pending"] << ", failed "
      << j["failed"] << ", missing " << j["missing"] << "; frames missing " << j["missing_frames"].size()
      << "; assembled " << (status.assembled ? "yes" : "no") << "\n";
  int shown = 0;
  for (const FarmTaskState& t : status.tasks) {
    if (t.state == "done") continue;
    if (++shown > 50) {
      out << "  …\n";
      break;
    }
    out << "  task " << t.index << ": " << t.state;
    if (t.exit_status >= 0) out << " (exit " << t.exit_status << ")";
    if (!t.missing_frames.empty()) {
      out << ", frames missing:";
      for (std::size_t k = 0; k < t.missing_frames.size() && k < 10; ++k) out << " " << t.missing_frames[k];
      if (t.missing_frames.size() > 10) out << " …";
    }
    if (!t.problem.empty()) out << " (" << t.problem << ")";
    out << "\n";
  }
}

int farm_submit(FarmPlan plan, std::ostream& out, std::ostream& err) {
  bool planned = false;  // farm.json written
  const std::string what = plan.kind == "batch" ? "farm batch: " : "farm submit: ";
  try {
    plan.dir = fs::absolute(plan.dir).lexically_normal();
    if (plan.dir.filename().empty()) plan.dir = plan.dir.parent_path();
    if (const std::string bad = slurm_folder_error(plan); !bad.empty()) throw std::invalid_argument(bad);
    std::error_code ec;
    if (fs::exists(plan.dir, ec) && !fs::is_directory(plan.dir, ec))
      throw std::invalid_argument("--out '" + plan.dir.string() + "' is a file, not a folder");
    if (plan.kind == "frames") {
      plan.log = fs::absolute(plan.log).lexically_normal();
      const std::optional<FileSum> sum = file_sum(plan.log, kFarmMaxLogBytes, true);
      if (!sum) throw std::invalid_argument("cannot read the log '" + plan.log.string() + "' (or it is over 1 GiB)");
      plan.log_crc32 = sum->crc32;
      plan.log_bytes = sum->bytes;
      plan.tasks = plan_frames(plan.frame_first, plan.frame_last, plan.chunk);
      core::Scene scene;
      const std::string bad = check_range(plan, scene);
      if (!bad.empty()) throw std::invalid_argument(bad);
      plan.fps = scene.timeline.fps;
      const core::Camera camera = render_camera(scene, plan.width, plan.height);
      plan.frame_width = camera.viewport.x;
      plan.frame_height = camera.viewport.y;
    }
    check_farm_plan(plan);
    if (fs::exists(fs::symlink_status(plan.dir / "farm.json", ec))) {
      err << what << plan.dir.string()
          << " already holds a farm: `trispline farm resume` it, or choose another --out (nothing submitted)\n";
      return 2;
    }
    if (plan.engine == "slurm" && find_on_path("sbatch").empty()) {
      err << what
          << "sbatch not found on PATH: install Slurm's client commands (Debian: slurm-client, part of "
             "slurm-wlm) or use --engine local (nothing submitted)\n";
      return 2;
    }
    fs::create_directories(plan.dir);
    write_job_scripts(plan);
    write_plan(plan);
    planned = true;
    std::vector<int> all;
    for (const FarmTask& t : plan.tasks) all.push_back(t.index);
    return run_engine(plan, all, out);
  } catch (const std::invalid_argument& e) {
    err << what << e.what() << " (nothing submitted)\n";
    return 2;
  } catch (const FarmPlanError& e) {
    err << what << e.what() << " (nothing submitted)\n";
    return 2;
  } catch (const std::exception& e) {
    err << what << e.what() << "\n";
    if (planned)
      err << what << "the plan and job scripts stay in " << plan.dir.string() << ": `trispline farm resume "
          << plan.dir.string() << "` submits them\n";
    return 3;
  }
}

int farm_resume(const fs::path& dir_in, std::ostream& out, std::ostream& err) {
  try {
    FarmPlan plan = read_plan(dir_in);
    if (plan.kind == "frames")
      if (const std::string changed = log_change(plan.log, plan.log_crc32, plan.log_bytes); !changed.empty()) {
        err << "farm resume: " << changed << " (nothing resubmitted)\n";
        return 2;
      }
    if (const std::string bad = slurm_folder_error(plan); !bad.empty()) {
      err << "farm resume: " << bad << "\n";
      return 2;
    }
    if (local_pool_running(plan.dir)) {
      err << "farm resume: a local pool still runs in " << plan.dir.string() << ": wait for it or stop it first\n";
      return 2;
    }
    if (const int stopped = stop_stale_local_tasks(plan); stopped > 0)
      out << "farm resume: stopped " << stopped << " processes a killed local pool left running\n";
    bool stale = false;
    for (FarmJob& job : plan.jobs)
      if (job.engine == "local" && (job.pool_pid != 0 || !job.task_pids.empty())) {
        job.pool_pid = 0;
        job.task_pids.clear();
        stale = true;
      }
    if (stale) write_plan(plan);
    const FarmStatus status = farm_status(plan.dir);
    for (const FarmTaskState& t : status.tasks)
      if (t.state == "running" || t.state == "pending") {
        err << "farm resume: task " << t.index << " is still " << t.state
            << ": wait for it (trispline farm status) or cancel the job first\n";
        return 2;
      }
    const std::vector<int> tasks = tasks_to_resume(status);
    if (tasks.empty()) {
      out << "farm resume: every task's output is there";
      if (status.assembled) {
        out << "; nothing to do\n";
        return 0;
      }
      out << "; assembling\n";
      return farm_assemble(plan.dir, out, err) == 0 ? 0 : 1;
    }
    if (plan.engine == "slurm" && find_on_path("sbatch").empty()) {
      err << "farm resume: sbatch not found on PATH: install Slurm's client commands (Debian: slurm-client, part of "
             "slurm-wlm)\n";
      return 2;
    }
    // The scripts are written again, by this build for this build: the folder's own copies are not trusted (a
    // shared farm may hold edited ones), and the executable may have moved since submission.
    std::error_code ec;
    if (const fs::path self = fs::read_symlink("/proc/self/exe", ec); !ec && self.is_absolute()) plan.trispline = self;
    check_farm_plan(plan);
    write_job_scripts(plan);
    write_plan(plan);
    return run_engine(plan, tasks, out);
  } catch (const std::exception& e) {
    err << "farm resume: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace trispline::editor
