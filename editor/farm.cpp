#include "editor/farm.h"

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/commands/anim_record.h"
#include "editor/history.h"
#include "editor/record.h"
#include "editor/render_scene.h"
#include "editor/replay.h"

namespace trispline::editor {
namespace fs = std::filesystem;

namespace {

// A word for bash: single-quoted, a single quote as '\''.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void write_text_atomically(const fs::path& path, const std::string& text, bool executable) {
  const fs::path tmp = path.string() + ".tmp";
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

// The #SBATCH lines both scripts share.
std::string sbatch_header(const FarmPlan& plan, const std::string& name, const fs::path& log) {
  std::string h = "#SBATCH --job-name=" + name + "\n#SBATCH --output=" + log.string() + "\n";
  if (!plan.partition.empty()) h += "#SBATCH --partition=" + plan.partition + "\n";
  if (!plan.time_limit.empty()) h += "#SBATCH --time=" + plan.time_limit + "\n";
  return h;
}

std::string task_script(const FarmPlan& plan) {
  const std::string exe = shell_quote(plan.trispline.string());
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# trispline farm: one array task (SLURM_ARRAY_TASK_ID) of " << plan.dir.string()
    << "; written by `trispline farm " << (plan.kind == "batch" ? "batch" : "submit") << "`.\n"
    << sbatch_header(plan, "trispline-farm", plan.dir / "logs" / "task_%4a.log") << "#SBATCH --cpus-per-task=1\n"
    << "set -u\n"
    << "task=${SLURM_ARRAY_TASK_ID:?run by sbatch --array or by trispline farm --engine local}\n"
    << "# llvmpipe draws with the CPUs the task was given, not every CPU of the node\n"
    << "export LP_NUM_THREADS=${LP_NUM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}\n";
  if (plan.kind == "batch") {
    s << "logs=(";
    for (const FarmTask& t : plan.tasks) s << "\n  " << shell_quote(t.log.string());
    s << "\n)\nnames=(";
    for (const FarmTask& t : plan.tasks) s << " " << shell_quote(t.name);
    s << " )\n"
      << "out=" << shell_quote((plan.dir / "runs").string()) << "/${names[$task]}\n"
      << "echo \"farm: task $task log ${logs[$task]} start $(date +%s.%N) on $(hostname)\"\n"
      << exe << " replay \"${logs[$task]}\" --out \"$out\"";
  } else {
    s << "first=$((" << plan.frame_first << " + task * " << plan.chunk << "))\n"
      << "last=$((first + " << plan.chunk - 1 << "))\n"
      << "if ((last > " << plan.frame_last << ")); then last=" << plan.frame_last << "; fi\n"
      << "out=" << shell_quote((plan.dir / "chunks").string()) << "/$(printf %04d \"$task\")\n"
      << "echo \"farm: task $task frames $first-$last start $(date +%s.%N) on $(hostname)\"\n"
      << exe << " replay " << shell_quote(plan.log.string())
      << " --frames \"$first-$last\" --out \"$out\" --no-render --format " << plan.format << " --piece-base "
      << plan.frame_first;
  }
  if (plan.width > 0) s << " --width " << plan.width << " --height " << plan.height;
  s << "\nstatus=$?\n"
    << "echo \"farm: task $task exit $status end $(date +%s.%N)\"\n"
    << "exit $status\n";
  return s.str();
}

std::string assemble_script(const FarmPlan& plan) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# trispline farm: the assemble step of " << plan.dir.string() << ", after every task.\n"
    << sbatch_header(plan, "trispline-farm-assemble", plan.dir / "logs" / "assemble.log")
    << "#SBATCH --cpus-per-task=1\n"
    << "exec " << shell_quote(plan.trispline.string()) << " farm assemble " << shell_quote(plan.dir.string()) << "\n";
  return s.str();
}

// A task log's "farm: task K … start T" and "farm: task K exit S end T" lines.
void read_task_log(const fs::path& log, FarmTaskState& st) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("farm: task ", 0) != 0) continue;
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    for (std::size_t i = 0; i + 1 < w.size(); ++i) {
      try {
        if (w[i] == "start") st.start_s = std::stod(w[i + 1]);
        if (w[i] == "end") st.end_s = std::stod(w[i + 1]);
        if (w[i] == "exit") st.exit_status = std::stoi(w[i + 1]);
      } catch (const std::exception&) {
      }
    }
  }
}

bool process_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

// Replays the plan's log (no rendering) and checks the frame range against its timeline: "" when it fits.
std::string check_range(const FarmPlan& plan, core::Scene& scene) {
  History history(scene);
  const ReplayResult r = replay_lines(history, plan.log);
  if (!r.ok) return "the log does not replay: " + r.error;
  const std::string err = core::frame_range_error(scene.timeline, plan.frame_first, plan.frame_last);
  return err.empty()
             ? ""
             : "--frames " + std::to_string(plan.frame_first) + "-" + std::to_string(plan.frame_last) + ": " + err;
}

// Runs `tasks` with the plan's engine, records the job in farm.json and prints what happened.
int run_engine(FarmPlan& plan, const std::vector<int>& tasks, std::ostream& out) {
  std::string list;
  for (int t : tasks) list += (list.empty() ? "" : ",") + std::to_string(t);
  if (plan.engine == "slurm") {
    for (const FarmJob& old : plan.jobs)  // an assembly still waiting on a failed array would never start
      if (old.engine == "slurm" && !old.assemble_id.empty()) cancel_slurm_job(old.assemble_id);
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
    plan.jobs.push_back(job);
    write_plan(plan);
    started = true;
  });
  if (started) {
    plan.jobs.back().pool_pid = 0;  // the pool has finished
    write_plan(plan);
  }
  return rc;
}

}  // namespace

std::string farm_task_name(int index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04d", index);
  return buf;
}

namespace {

// Every field of farm.json once, for writing and reading: visit(name, member) per field, tasks and jobs included.
template <class Plan, class Visit>
void visit_plan_fields(Plan& p, Visit&& visit) {
  visit("kind", p.kind);
  visit("dir", p.dir);
  visit("trispline", p.trispline);
  visit("log", p.log);
  visit("frame_first", p.frame_first);
  visit("frame_last", p.frame_last);
  visit("chunk", p.chunk);
  visit("format", p.format);
  visit("width", p.width);
  visit("height", p.height);
  visit("fps", p.fps);
  visit("frame_width", p.frame_width);
  visit("frame_height", p.frame_height);
  visit("engine", p.engine);
  visit("max_parallel", p.max_parallel);
  visit("partition", p.partition);
  visit("time", p.time_limit);
  visit("tasks", p.tasks);
  visit("jobs", p.jobs);
}

}  // namespace

// farm.json's "tasks" and "jobs" entries (found by the plan's conversions through ADL).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FarmTask, index, first, last, log, name)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FarmJob, engine, array_id, assemble_id, pool_pid, tasks)

nlohmann::json FarmPlan::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  visit_plan_fields(*this, [&](const char* name, const auto& value) { j[name] = value; });
  return j;
}

FarmPlan FarmPlan::from_json(const nlohmann::json& j) {
  FarmPlan p;
  std::string field;
  try {
    visit_plan_fields(p, [&](const char* name, auto& value) {
      field = name;
      j.at(name).get_to(value);
    });
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("farm.json: field '" + field + "': " + e.what());
  }
  return p;
}

std::vector<FarmTask> plan_frames(int first, int last, int chunk) {
  if (chunk <= 0) throw std::invalid_argument("--chunk must be at least 1 frame, got " + std::to_string(chunk));
  if (first < 0 || first > last)
    throw std::invalid_argument("frame range " + std::to_string(first) + "-" + std::to_string(last) +
                                " is empty or negative");
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

std::vector<FarmTask> plan_batch(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw std::invalid_argument("no folder '" + folder.string() + "'");
  std::vector<fs::path> logs;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.is_regular_file() && e.path().extension() == ".jsonl") logs.push_back(fs::absolute(e.path()));
  if (logs.empty()) throw std::invalid_argument("'" + folder.string() + "' holds no command log (*.jsonl)");
  std::sort(logs.begin(), logs.end());
  std::vector<FarmTask> tasks;
  std::set<std::string> names;
  for (const fs::path& log : logs) {
    FarmTask t;
    t.index = static_cast<int>(tasks.size());
    t.log = log;
    t.name = log.stem().string();
    for (int k = 2; names.count(t.name); ++k) t.name = log.stem().string() + "_" + std::to_string(k);
    names.insert(t.name);
    tasks.push_back(t);
  }
  return tasks;
}

FarmPlan read_plan(const fs::path& dir) {
  const fs::path path = dir / "farm.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("no farm in '" + dir.string() + "' (" + path.string() + " is missing)");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
  return FarmPlan::from_json(j);
}

void write_plan(const FarmPlan& plan) {
  write_text_atomically(plan.dir / "farm.json", plan.to_json().dump(2) + "\n", false);
}

void write_job_scripts(const FarmPlan& plan) {
  fs::create_directories(plan.dir / "logs");
  write_text_atomically(plan.dir / "farm_task.sh", task_script(plan), true);
  write_text_atomically(plan.dir / "farm_assemble.sh", assemble_script(plan), true);
}

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
                       {"missing_frames", t.missing_frames}});
  }
  nlohmann::json j = {{"tasks", tasks_j}, {"missing_frames", missing}, {"assembled", assembled}};
  for (const auto& [name, n] : counts) j[name] = n;
  return j;
}

FarmStatus farm_status(const fs::path& dir) {
  const FarmPlan plan = read_plan(dir);
  std::set<int> queued;  // tasks a Slurm job or the local pool still runs
  for (const FarmJob& job : plan.jobs) {
    if (job.engine == "local" && process_alive(job.pool_pid)) queued.insert(job.tasks.begin(), job.tasks.end());
    if (job.engine != "slurm") continue;
    for (const std::string& id : slurm_active_tasks(job)) {
      const std::size_t us = id.find('_');
      if (us == std::string::npos) continue;
      try {
        queued.insert(std::stoi(id.substr(us + 1)));
      } catch (const std::exception&) {
      }
    }
  }
  FarmStatus status;
  std::error_code ec;
  bool all_frames_in_dir = true;
  for (const FarmTask& t : plan.tasks) {
    FarmTaskState st;
    st.index = t.index;
    read_task_log(dir / "logs" / ("task_" + farm_task_name(t.index) + ".log"), st);
    bool output = true;
    if (plan.kind == "batch") {
      output = fs::is_regular_file(dir / "runs" / t.name / "report.json", ec);
    } else {
      const fs::path chunk = dir / "chunks" / farm_task_name(t.index);
      for (int f = t.first; f <= t.last; ++f) {
        if (!fs::is_regular_file(chunk / frame_file_name(f, plan.format), ec)) st.missing_frames.push_back(f);
        all_frames_in_dir = all_frames_in_dir && fs::is_regular_file(dir / frame_file_name(f, plan.format), ec);
      }
      output = st.missing_frames.empty() && fs::is_regular_file(chunk / "animation.piece", ec);
    }
    const bool ended = st.end_s > 0;
    if (queued.count(t.index))
      st.state = st.start_s > 0 && !ended ? "running" : "pending";
    else if (ended && st.exit_status != 0)
      st.state = "failed";
    else if (output)
      st.state = "done";
    else if (st.start_s > 0 && !ended)
      st.state = "failed";  // started, never ended and no longer queued: killed (time limit, node lost)
    else
      st.state = "missing";
    status.tasks.push_back(st);
  }
  const bool all_done =
      std::all_of(status.tasks.begin(), status.tasks.end(), [](const FarmTaskState& t) { return t.state == "done"; });
  status.assembled = plan.kind == "batch"
                         ? fs::is_regular_file(dir / "summary.json", ec)
                         : all_done && all_frames_in_dir && fs::is_regular_file(dir / "animation.glb", ec);
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
  out << "  done " << j["done"] << ", running " << j["running"] << ", pending " << j["pending"] << ", failed "
      << j["failed"] << ", missing " << j["missing"] << "; frames missing " << j["missing_frames"].size()
      << "; assembled " << (status.assembled ? "yes" : "no") << "\n";
  for (const FarmTaskState& t : status.tasks) {
    if (t.state == "done") continue;
    out << "  task " << t.index << ": " << t.state;
    if (t.exit_status >= 0) out << " (exit " << t.exit_status << ")";
    if (!t.missing_frames.empty()) {
      out << ", frames missing:";
      for (std::size_t k = 0; k < t.missing_frames.size() && k < 10; ++k) out << " " << t.missing_frames[k];
      if (t.missing_frames.size() > 10) out << " …";
    }
    out << "\n";
  }
}

int farm_submit(FarmPlan plan, std::ostream& out, std::ostream& err) {
  bool planned = false;  // farm.json written
  try {
    plan.dir = fs::absolute(plan.dir).lexically_normal();
    if (plan.kind == "frames") {
      plan.log = fs::absolute(plan.log).lexically_normal();
      plan.tasks = plan_frames(plan.frame_first, plan.frame_last, plan.chunk);
      core::Scene scene;
      const std::string bad = check_range(plan, scene);
      if (!bad.empty()) {
        err << "farm submit: " << bad << " (nothing submitted)\n";
        return 2;
      }
      plan.fps = scene.timeline.fps;
      const core::Camera camera = render_camera(scene, plan.width, plan.height);
      plan.frame_width = camera.viewport.x;
      plan.frame_height = camera.viewport.y;
    }
    std::error_code ec;
    if (fs::is_regular_file(plan.dir / "farm.json", ec)) {
      err << "farm submit: " << plan.dir.string()
          << " already holds a farm: `trispline farm resume` it, or choose another --out (nothing submitted)\n";
      return 2;
    }
    if (plan.engine == "slurm" && find_on_path("sbatch").empty()) {
      err << "farm submit: sbatch not found on PATH: install Slurm's client commands (Debian: slurm-client, part of "
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
    err << "farm submit: " << e.what() << " (nothing submitted)\n";
    return 2;
  } catch (const std::exception& e) {
    err << "farm submit: " << e.what() << "\n";
    if (planned)
      err << "farm submit: the plan and job scripts stay in " << plan.dir.string() << ": `trispline farm resume "
          << plan.dir.string() << "` submits them\n";
    return 3;
  }
}

int farm_resume(const fs::path& dir_in, std::ostream& out, std::ostream& err) {
  try {
    const fs::path dir = fs::absolute(dir_in).lexically_normal();
    FarmPlan plan = read_plan(dir);
    const FarmStatus status = farm_status(dir);
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
      return farm_assemble(dir, out, err) == 0 ? 0 : 1;
    }
    if (plan.engine == "slurm" && find_on_path("sbatch").empty()) {
      err << "farm resume: sbatch not found on PATH: install Slurm's client commands (Debian: slurm-client, part of "
             "slurm-wlm)\n";
      return 2;
    }
    return run_engine(plan, tasks, out);
  } catch (const std::exception& e) {
    err << "farm resume: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace trispline::editor
