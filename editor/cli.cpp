#include "editor/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <iostream>

#include "core/ffd/ffd_evaluator.h"
#include "editor/app.h"
#include "bench/bench_ffd.h"
#include "bench/bench_ddm.h"
#include "bench/bench_dffd.h"
#include "bench/bench_place.h"
#include "editor/command_docs.h"
#include "editor/command_registry.h"
#include "editor/replay.h"

namespace trispline::editor {

namespace {

// Rewrites the generated parameter tables of a Markdown file in place (written whole, then renamed over it).
int rewrite_command_docs(const std::string& path, const CommandRegistry& registry) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "trispline commands: cannot read " << path << "\n";
    return 2;
  }
  std::stringstream text;
  text << in.rdbuf();
  const std::string updated = with_generated_tables(text.str(), registry);
  const std::string tmp = path + ".tmp";
  std::ofstream(tmp, std::ios::binary) << updated;
  std::filesystem::rename(tmp, path);
  std::cout << (updated == text.str() ? "unchanged: " : "updated: ") << path << "\n";
  return 0;
}

}  // namespace

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
  edit->add_option("--gui-probe", edit_options.gui_probe,
                   "Write widget rectangles, popups, history and log as JSON to this file every frame (GUI tests)");
  edit->add_option("--max-fps", edit_options.max_fps, "Draw at most this many frames per second (GUI tests: 3)")
      ->check(CLI::NonNegativeNumber);
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
  replay
      ->add_option_function<std::string>(
          "--ffd-backend",
          [&replay_options](const std::string& name) {
            replay_options.ffd_backend = *core::parse_ffd_backend(name);  // checked below
          },
          "FFD evaluator for final.png and scene.glb: cpu_ref (default, the authoritative geometry), cpu_fast, "
          "glsl_compute or glsl_vertex (scene.glb is then read back from the GPU)")
      ->check(
          [](const std::string& name) -> std::string {
            if (core::parse_ffd_backend(name)) return {};
            return "unknown FFD backend '" + name + "': use cpu_ref, cpu_fast, glsl_compute or glsl_vertex";
          },
          "BACKEND");
  replay
      ->add_option("--time", replay_options.time_s,
                   "Scene time in seconds: animated objects (lattice.animate_offset) are drawn and exported at it")
      ->check(
          [](const std::string& text) -> std::string {
            try {
              std::size_t used = 0;
              const double t = std::stod(text, &used);
              if (used == text.size() && std::isfinite(t)) return {};
            } catch (const std::exception&) {
            }
            return "--time needs a finite number of seconds, got '" + text + "'";
          },
          "SECONDS");

  replay
      ->add_option_function<std::string>(
          "--frames",
          [&replay_options](const std::string& text) {
            const auto range = parse_frame_range(text);  // checked below
            replay_options.frames_given = true;
            replay_options.frame_first = range->first;
            replay_options.frame_last = range->second;
          },
          "Record timeline frames A-B (inclusive) of the final scene into --out: frame_NNNN.png|exr and "
          "animation.glb of that range (exit 2, nothing written, when the range lies outside the timeline)")
      ->check(
          [](const std::string& text) -> std::string {
            return parse_frame_range(text) ? "" : "--frames needs A-B with 0 <= A <= B, got '" + text + "'";
          },
          "A-B");
  replay->add_option("--format", replay_options.format, "Image format of --frames: png (8-bit) or exr (half, linear)")
      ->check(CLI::IsMember({"png", "exr"}));

  auto* bench = app.add_subcommand("bench", "Benchmarks that print figures (never assert timings)");
  bench->require_subcommand(1);
  BenchFfdOptions bench_options;
  auto* bench_ffd = bench->add_subcommand(
      "ffd", "FFD throughput of every evaluator backend (CPU reference/fast, GLSL compute/vertex) on the bunny "
             "subdivided to ~0.8 M vertices, 4^3 and 8^3 lattices, orders 3 and 4");
  bench_ffd->add_flag("--json", bench_options.json, "Print one JSON object instead of a table");
  bench_ffd->add_option("--mesh", bench_options.mesh_path,
                        "Benchmark this mesh's vertices instead (OBJ/PLY/OFF/STL/glTF; default: the bunny)")
      ->check(CLI::ExistingFile);
  bench_ffd->add_option("--subdiv", bench_options.subdivision,
                        "OpenSubdiv bilinear subdivision levels (default 2 for the bunny, 0 for --mesh)")
      ->check(CLI::Range(0, 6));
  bench_ffd->add_option("--runs", bench_options.runs, "Timed runs per case; the median is reported")
      ->check(CLI::Range(1, 1000));
  bench_ffd->add_flag("!--cpu-only", bench_options.gpu, "Skip the GLSL backends (no GL context)");
  bench_ffd->add_option("--gpu-shaders", bench_options.gpu_shaders,
                        "How GLSL shaders get the orders: auto (generic on software renderers), specialised, generic")
      ->check(CLI::IsMember({"auto", "specialised", "generic"}));

  BenchPlaceOptions place_bench;
  std::vector<int> place_samples{place_bench.samples_u, place_bench.samples_v};
  bool springs_on_only = false, springs_off_only = false;
  auto* bench_place = bench->add_subcommand(
      "place", "place.sketch end to end (stroke -> placed bunny over the teapot and the terrain), ms per stage, "
               "mass-spring contact surface on and off");
  bench_place->add_flag("--json", place_bench.json, "Print one JSON object instead of a table");
  bench_place->add_option("--runs", place_bench.runs, "Timed runs per case after one warm-up; the median is reported")
      ->check(CLI::Range(1, 1000));
  bench_place->add_option("--mesh", place_bench.mesh_path, "Place this mesh instead of assets/data/bunny.obj")
      ->check(CLI::ExistingFile);
  bench_place->add_option("--samples", place_samples, "Contact rays NU NV (default 64 8)")
      ->expected(2)
      ->check(CLI::Range(2, 4096));
  auto* on_only = bench_place->add_flag("--springs", springs_on_only, "Only with the mass-spring contact surface");
  bench_place->add_flag("--no-springs", springs_off_only, "Only without the mass-spring contact surface")
      ->excludes(on_only);
  bench_place->add_option("--scene", place_bench.scenes, "Scenes: teapot, terrain (default both)")
      ->check(CLI::IsMember({"teapot", "terrain"}));

  BenchDffdOptions dffd_bench;
  auto* bench_dffd = bench->add_subcommand(
      "dffd", "Discontinuous FFD per frame: split + cap + deform of the bunny walking through bars (seed §6.3)");
  bench_dffd->add_flag("--json", dffd_bench.json, "Print one JSON object instead of a table");
  bench_dffd->add_option("--scene", dffd_bench.scene_path, "Scene log with an animated dffd.split object")
      ->default_str("assets/scenes/bars_walk.jsonl");
  bench_dffd->add_option("--runs", dffd_bench.runs, "Timed evaluations per frame (median)")->check(CLI::PositiveNumber);
  bench_dffd->add_option("--frames", dffd_bench.frames, "Frames sampled over the walk")->check(CLI::PositiveNumber);
  BenchDdmOptions ddm_bench;
  auto* bench_ddm = bench->add_subcommand(
      "ddm", "Live DDM layers drawn by GPU instancing: tile vertices, GPU ms per frame, fps (seed §5.3.2, Table 5.1)");
  bench_ddm->add_flag("--json", ddm_bench.json, "Print one JSON object instead of a table");
  bench_ddm->add_option("--frames", ddm_bench.frames, "Timed frames per case (after 2 warm-up frames)")
      ->check(CLI::PositiveNumber);
  bench_ddm->add_option("--width", ddm_bench.width, "Offscreen target width, pixels")->check(CLI::PositiveNumber);
  bench_ddm->add_option("--height", ddm_bench.height, "Offscreen target height, pixels")->check(CLI::PositiveNumber);
  bench_ddm->add_option("--samples", ddm_bench.samples, "MSAA samples")->check(CLI::Range(1, 16));
  bench_ddm->add_option("--case", ddm_bench.cases, "Cases: thorns_face, thorns_teapot, chains_1m, chains_3m (default all)")
      ->check(CLI::IsMember({"thorns_face", "thorns_teapot", "chains_1m", "chains_3m"}));
  bench_ddm->add_flag("!--no-cpu", ddm_bench.cpu_reference, "Do not time the CPU reference evaluation");
  BenchPressOptions press_bench;
  auto* bench_press = bench->add_subcommand(
      "press", "A pressing drag on a ~1 M-vertex object: Press tool per mouse move, pressed lattice, cpu_fast / GLSL "
               "re-evaluation per drag sample, and the lattice.press command at release");
  bench_press->add_flag("--json", press_bench.json, "Print one JSON object instead of a table");
  bench_press->add_option("--vertices", press_bench.vertices,
                          "Target vertex count: the bunny's subdivision level closest to it (default 1000000)")
      ->check(CLI::Range(8, 100000000));
  bench_press->add_option("--runs", press_bench.runs, "Drags, timed updates and command runs (median)")
      ->check(CLI::Range(1, 1000));
  bench_press->add_option("--mesh", press_bench.mesh_path, "Use this mesh instead of assets/data/bunny.obj")
      ->check(CLI::ExistingFile);
  bench_press->add_flag("!--cpu-only", press_bench.gpu, "Skip glsl_compute (no GL context)");

  auto* commands = app.add_subcommand("commands", "List the commands a log may contain");
  std::string command_id, docs_file;
  commands->add_option("id", command_id, "Show this command's parameters as a Markdown table");
  commands->add_option("--docs", docs_file,
                       "Rewrite the generated parameter tables (<!-- params: ID --> blocks) of this Markdown file");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*replay) return run_replay(replay_options);
    if (*bench_ffd) return run_bench_ffd(bench_options, std::cout, std::cerr);
    if (*bench_place) {
      place_bench.samples_u = place_samples.at(0);
      place_bench.samples_v = place_samples.at(1);
      place_bench.springs = springs_on_only ? "on" : springs_off_only ? "off" : "both";
      return run_bench_place(place_bench, std::cout, std::cerr);
    }
    if (*bench_dffd) return run_bench_dffd(dffd_bench, std::cout, std::cerr);
    if (*bench_ddm) return run_bench_ddm(ddm_bench, std::cout, std::cerr);
    if (*bench_press) return run_bench_press(press_bench, std::cout, std::cerr);
    if (*commands) {
      const auto& registry = CommandRegistry::builtin();
      if (!docs_file.empty()) return rewrite_command_docs(docs_file, registry);
      if (!command_id.empty()) {
        const auto ids = registry.ids();
        if (std::find(ids.begin(), ids.end(), command_id) == ids.end()) {
          std::cerr << "trispline commands: no command '" << command_id << "' (trispline commands lists them)\n";
          return 2;
        }
        std::cout << "# " << command_id << "\n" << registry.summary(command_id) << "\n\n"
                  << params_table(registry, command_id);
        return 0;
      }
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
