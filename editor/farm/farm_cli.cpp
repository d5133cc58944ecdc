#include "editor/farm/farm_cli.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "core/commands/anim_record.h"
#include "editor/replay/replay.h"

namespace trispline::editor {
namespace {

// The options submit and batch share: engine, parallelism, Slurm's partition and time limit, frame size.
void add_engine_options(CLI::App* cmd, FarmCli& o) {
  cmd->add_option("--out", o.plan.dir, "Farm folder (created; on a filesystem every node sees)")->required();
  cmd->add_option("--engine", o.plan.engine, "slurm (sbatch array job, default) or local (a pool on this machine)")
      ->check(CLI::IsMember({"slurm", "local"}));
  cmd->add_option("--max-parallel", o.plan.max_parallel,
                  "Tasks running at once (Slurm: --array=…%N; 0 = no limit, local: the number of CPUs)")
      ->check(CLI::Range(0, kFarmMaxParallel));
  cmd->add_option("--partition", o.plan.partition, "Slurm partition (default: the cluster's default)")
      ->check([](const std::string& p) { return check_sbatch_value("--partition", p); }, "NAME");
  cmd->add_option("--time", o.plan.time_limit, "Slurm time limit per task, HH:MM:SS")
      ->check(
          [](const std::string& t) -> std::string {
            if (const std::string bad = check_sbatch_value("--time", t); !bad.empty()) return bad;
            const bool ok = t.size() >= 5 && t.find_first_not_of("0123456789:-") == std::string::npos;
            return ok ? "" : "--time needs HH:MM:SS (or Slurm's D-HH:MM:SS), got '" + t + "'";
          },
          "HH:MM:SS");
  auto* w = cmd->add_option("--width", o.plan.width, "Frame width in pixels (default: the camera's viewport)")
                ->check(CLI::Range(1, 16384));
  auto* h = cmd->add_option("--height", o.plan.height, "Frame height in pixels")->check(CLI::Range(1, 16384));
  w->needs(h);
  h->needs(w);
  // The frame budget of anim.record, checked before farm.json is written (a bad value exits 2).
  cmd->parse_complete_callback([&o] {
    if (const std::string problem = core::frame_budget_problem(o.plan.width, o.plan.height); !problem.empty())
      throw CLI::ValidationError("--width", problem);
  });
}

std::filesystem::path own_executable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the trispline executable (/proc/self/exe): " + ec.message());
  return self;
}

}  // namespace

void add_farm_commands(CLI::App& app, FarmCli& o) {
  auto* farm = app.add_subcommand(
      "farm", "Render a long recording or replay many logs as array jobs: on Slurm (sbatch) or a local pool");
  farm->require_subcommand(1);

  o.submit = farm->add_subcommand(
      "submit",
      "Cut --frames into chunks, one array task per chunk (trispline replay LOG --frames a-b), then an "
      "assemble job (afterok): every frame checked, animation.glb joined, MP4 when ffmpeg is there");
  o.submit->add_option("log", o.plan.log, "Command log (.jsonl)")->required()->check(CLI::ExistingFile);
  o.submit->add_option("--frames", o.frames, "Timeline frames A-B (inclusive)")
      ->required()
      ->check(
          [](const std::string& text) -> std::string {
            return parse_frame_range(text) ? "" : "--frames needs A-B with 0 <= A <= B, got '" + text + "'";
          },
          "A-B");
  o.submit->add_option("--chunk", o.plan.chunk, "Frames per task")->required();
  o.submit->add_option("--format", o.plan.format, "Image format: png (8-bit) or exr (half, linear)")
      ->check(CLI::IsMember({"png", "exr"}));
  add_engine_options(o.submit, o);

  o.batch = farm->add_subcommand(
      "batch",
      "Replay every *.jsonl of a folder, one array task per log (trispline replay LOG --out DIR/runs/NAME), "
      "then an assemble job (afterany) that collects every report.json into DIR/summary.json");
  o.batch->add_option("folder", o.batch_folder, "Folder of command logs")->required()->check(CLI::ExistingDirectory);
  add_engine_options(o.batch, o);

  o.status = farm->add_subcommand("status", "Tasks done / running / pending / failed and the frames missing");
  o.status->add_option("dir", o.dir, "Farm folder")->required()->check(CLI::ExistingDirectory);
  o.status->add_flag("--json", o.json, "Print one JSON object instead of text");

  o.resume = farm->add_subcommand("resume", "Resubmit only the tasks whose output is missing, then assemble again");
  o.resume->add_option("dir", o.dir, "Farm folder")->required()->check(CLI::ExistingDirectory);

  o.assemble = farm->add_subcommand(
      "assemble", "The assemble step (the job scripts run it): check the frames, join animation.glb, MP4, report");
  o.assemble->add_option("dir", o.dir, "Farm folder")->required()->check(CLI::ExistingDirectory);

  o.task = farm->add_subcommand(
      "task", "One array task (what farm_task.sh runs): check the plan and the log, replay task K, record its files");
  o.task->add_option("dir", o.dir, "Farm folder")->required()->check(CLI::ExistingDirectory);
  o.task->add_option("index", o.task_index, "Task number (SLURM_ARRAY_TASK_ID)")
      ->required()
      ->check(CLI::Range(0, kFarmMaxFrame));
}

int run_farm_command(FarmCli& o) {
  if (*o.submit || *o.batch) {
    o.plan.trispline = own_executable();
    if (*o.submit) {
      o.plan.kind = "frames";
      const auto range = parse_frame_range(o.frames);  // checked by CLI11
      o.plan.frame_first = range->first;
      o.plan.frame_last = range->second;
    } else {
      o.plan.kind = "batch";
      try {
        o.plan.tasks = plan_batch(o.batch_folder);
      } catch (const std::exception& e) {
        std::cerr << "farm batch: " << e.what() << " (nothing submitted)\n";
        return 2;
      }
    }
    return farm_submit(o.plan, std::cout, std::cerr);
  }
  if (*o.status) {
    try {
      const FarmPlan plan = read_plan(o.dir);
      const FarmStatus status = farm_status(o.dir);
      if (o.json)
        std::cout << status.to_json().dump(2) << "\n";
      else
        print_farm_status(plan, status, std::cout);
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "farm status: " << e.what() << "\n";
      return 2;
    }
  }
  if (*o.resume) return farm_resume(o.dir, std::cout, std::cerr);
  if (*o.assemble) return farm_assemble(o.dir, std::cout, std::cerr);
  if (*o.task) return farm_task(o.dir, o.task_index, std::cout, std::cerr);
  return -1;
}

}  // namespace trispline::editor
