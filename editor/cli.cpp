#include "editor/cli.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "core/deform/ffd_bench.h"
#include "editor/app.h"
#include "editor/command_registry.h"
#include "editor/replay.h"

namespace trispline::editor {

int run_cli(int argc, char** argv) {
  CLI::App app{"trispline — interactive modeling with trivariate B-spline functions"};
  app.require_subcommand(0, 1);

  AppOptions edit_options;
  std::string open_log;
  app.add_option("log", open_log, "Command log (.jsonl) to open in the editor (same as `trispline edit LOG`)");
  auto* edit = app.add_subcommand("edit", "Open the editor (the default when no subcommand is given)");
  edit->add_option("log", open_log, "Command log (.jsonl) to open: replayed as undoable history");
  edit->add_option("--screenshot", edit_options.screenshot, "Render a few frames, write this PNG of the window, exit");
  edit->add_option("--width", edit_options.width, "Window width in pixels");
  edit->add_option("--height", edit_options.height, "Window height in pixels");
  edit->add_flag("!--no-recover", edit_options.recover_prompt, "Do not offer to recover an unfinished session");

  ReplayOptions replay_options;
  auto* replay =
      app.add_subcommand("replay", "Replay a command log headlessly and write final.png, scene.glb, report.json");
  replay->add_option("log", replay_options.log, "Command log (.jsonl)")->required()->check(CLI::ExistingFile);
  replay->add_option("--out", replay_options.out_dir, "Output folder")->required();
  auto* rw =
      replay->add_option("--width", replay_options.width, "final.png width in pixels (default: the camera's viewport)")
          ->check(CLI::Range(1, 16384));
  auto* rh =
      replay->add_option("--height", replay_options.height, "final.png height in pixels")->check(CLI::Range(1, 16384));
  rw->needs(rh);
  rh->needs(rw);
  replay->add_flag("!--no-render", replay_options.render, "Skip final.png (no GL context needed)");

  auto* bench = app.add_subcommand("bench", "Benchmarks that print figures (never assert timings)");
  bench->require_subcommand(1);
  core::FfdBenchOptions bench_options;
  bool bench_json = false;
  auto* bench_ffd = bench->add_subcommand("ffd", "CPU FFD throughput on the bunny subdivided to ~0.8 M vertices");
  bench_ffd->add_flag("--json", bench_json, "Print one JSON object instead of a table");
  bench_ffd->add_option("--mesh", bench_options.mesh_path, "Mesh to subdivide (default assets/data/bunny.obj)");

  auto* commands = app.add_subcommand("commands", "List the commands a log may contain");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*replay) return run_replay(replay_options);
    if (*bench_ffd) {
      const nlohmann::json result = core::run_ffd_benchmark(bench_options);
      if (bench_json)
        std::cout << result.dump() << "\n";
      else
        core::print_ffd_benchmark(result, std::cout);
      return 0;
    }
    if (*commands) {
      const auto& registry = CommandRegistry::builtin();
      for (const auto& id : registry.ids()) std::cout << id << "\t" << registry.summary(id) << "\n";
      std::cout << "edit.undo\tUndo the last command\nedit.redo\tRedo the last undone command\n";
      return 0;
    }
    if (!open_log.empty()) edit_options.open_log = open_log;
    return run_editor(edit_options);
  } catch (const std::exception& e) {
    std::cerr << "trispline: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace trispline::editor
