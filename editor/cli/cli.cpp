#include "editor/cli/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench/bench_ddm.h"
#include "bench/bench_dffd.h"
#include "bench/bench_editor.h"
#include "bench/bench_ffd.h"
#include "bench/bench_place.h"
#include "bench/bounds_bench.h"
#include "bench/silhouette_bench.h"
#include "core/commands/anim_record.h"
#include "core/ffd/ffd_evaluator.h"
#include "editor/app.h"
#include "editor/commands/command_docs.h"
#include "editor/commands/command_registry.h"
#include "editor/farm/farm_cli.h"
#include "editor/replay/replay.h"

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

// What the command line asked for: each subcommand's options, and the subcommand objects to test which one ran.
struct CliRequest {
  AppOptions edit;
  std::string open_log;
  ReplayOptions replay;
  CLI::App* replay_cmd = nullptr;
  BenchFfdOptions ffd;
  BenchPlaceOptions place;
  std::vector<int> place_samples{place.samples_u, place.samples_v};
  bool springs_on_only = false, springs_off_only = false;
  BenchDffdOptions dffd;
  BenchDdmOptions ddm;
  BenchPressOptions press;
  core::SilhouetteBenchOptions silhouettes;
  bool silhouettes_json = false;
  CLI::App* silhouettes_cmd = nullptr;
  EditorBenchOptions editor_bench;
  bool editor_bench_json = false;
  CLI::App* editor_bench_cmd = nullptr;
  core::BoundsBenchOptions bounds;
  bool bounds_json = false;
  CLI::App* bounds_cmd = nullptr;
  CLI::App *ffd_cmd = nullptr, *place_cmd = nullptr, *dffd_cmd = nullptr, *ddm_cmd = nullptr, *press_cmd = nullptr;
  CLI::App* commands_cmd = nullptr;
  std::string command_id, docs_file;
  FarmCli farm;
};

// `trispline [LOG]` and `trispline edit [LOG] [--screenshot PNG] ...`.
void add_edit(CLI::App& app, CliRequest& o) {
  app.add_option("log", o.open_log, "Command log (.jsonl) to open in the editor (same as `trispline edit LOG`)");
  CLI::App* edit = app.add_subcommand("edit", "Open the editor (the default when no subcommand is given)");
  edit->add_option("log", o.open_log, "Command log (.jsonl) to open: replayed as undoable history");
  edit->add_option("--screenshot", o.edit.screenshot, "Render a few frames, write this PNG of the window, exit");
  edit->add_option("--width", o.edit.width, "Window width in pixels");
  edit->add_option("--height", o.edit.height, "Window height in pixels");
  edit->add_option("--gui-probe", o.edit.gui_probe,
                   "Write widget rectangles, popups, history and log as JSON to this file every frame (GUI tests)");
  edit->add_option("--max-fps", o.edit.max_fps, "Draw at most this many frames per second (GUI tests: 3)")
      ->check(CLI::NonNegativeNumber);
  edit->add_option("--idle-fps", o.edit.idle_fps,
                   "Redraw this many times a second while nothing changes (default 0: an idle editor draws nothing; "
                   "GUI tests: 3)")
      ->check(CLI::NonNegativeNumber);
  edit->add_flag("!--no-recover", o.edit.recover_prompt, "Do not offer to recover an unfinished session");
  edit->add_option("--bench-out", o.edit.bench_out,
                   "Once the log is loaded, time idle and orbiting frames, write them as JSON here and exit "
                   "(`trispline bench editor` runs this)");
  edit->add_option("--bench-frames", o.edit.bench_frames, "Idle frames and orbiting frames --bench-out times")
      ->check(CLI::Range(1, 100000));
}

// `trispline replay LOG --out DIR [--frames A-B] ...`.
void add_replay(CLI::App& app, CliRequest& o) {
  o.replay_cmd =
      app.add_subcommand("replay", "Replay a command log headlessly and write final.png, scene.glb, report.json");
  o.replay_cmd->add_option("log", o.replay.log, "Command log (.jsonl)")->required()->check(CLI::ExistingFile);
  o.replay_cmd->add_option("--out", o.replay.out_dir, "Output folder")->required();
  auto* rw =
      o.replay_cmd->add_option("--width", o.replay.width, "final.png width in pixels (default: the camera's viewport)")
          ->check(CLI::Range(1, 16384));
  auto* rh =
      o.replay_cmd->add_option("--height", o.replay.height, "final.png height in pixels")->check(CLI::Range(1, 16384));
  rw->needs(rh);
  rh->needs(rw);
  o.replay_cmd->parse_complete_callback([&o] {  // the frame budget of anim.record, before the log is replayed
    if (const std::string problem = core::frame_budget_problem(o.replay.width, o.replay.height); !problem.empty())
      throw CLI::ValidationError("--width", problem);
  });
  o.replay_cmd->add_flag("!--no-render", o.replay.render, "Skip final.png (no GL context needed)");
  o.replay_cmd
      ->add_option_function<std::string>(
          "--ffd-backend",
          [&o](const std::string& name) {
            o.replay.ffd_backend = *core::parse_ffd_backend(name);  // checked below
          },
          "FFD evaluator for final.png and scene.glb: cpu_ref (default, the authoritative geometry), cpu_fast, "
          "glsl_compute or glsl_vertex (scene.glb is then read back from the GPU)")
      ->check(
          [](const std::string& name) -> std::string {
            if (core::parse_ffd_backend(name)) return {};
            return "unknown FFD backend '" + name + "': use cpu_ref, cpu_fast, glsl_compute or glsl_vertex";
          },
          "BACKEND");
  o.replay_cmd
      ->add_option("--time", o.replay.time_s,
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

  o.replay_cmd
      ->add_option_function<std::string>(
          "--frames",
          [&o](const std::string& text) {
            const auto range = parse_frame_range(text);  // checked below
            o.replay.frames_given = true;
            o.replay.frames.frame_first = range->first;
            o.replay.frames.frame_last = range->second;
          },
          "Record timeline frames A-B (inclusive) of the final scene into --out: frame_NNNN.png|exr and "
          "animation.glb of that range (exit 2, nothing written, when the range lies outside the timeline)")
      ->check(
          [](const std::string& text) -> std::string {
            return parse_frame_range(text) ? "" : "--frames needs A-B with 0 <= A <= B, got '" + text + "'";
          },
          "A-B");
  o.replay_cmd
      ->add_option("--format", o.replay.frames.format, "Image format of --frames: png (8-bit) or exr (half, linear)")
      ->check(CLI::IsMember({"png", "exr"}));
  o.replay_cmd
      ->add_option("--piece-base", o.replay.frames.piece_base,
                   "With --frames: write animation.piece, morph targets relative to this timeline frame (the farm's "
                   "range start), instead of animation.glb; `trispline farm assemble` joins the pieces")
      ->check(CLI::NonNegativeNumber)
      ->needs("--frames");
}

// `trispline bench silhouettes`: a table of the per-view figures, or the JSON object.
void print_silhouette_table(const nlohmann::json& r, std::ostream& out) {
  out << "silhouettes of " << r["volume"].get<std::string>() << " at iso " << r["iso"].get<double>() << ", order "
      << r["order"].get<int>() << ", dims " << r["dims"].dump() << ", " << r["threads"].get<int>() << " threads\n"
      << "  load " << bench_fixed(r["load_s"].get<double>(), 2) << " s, preprocessing "
      << bench_fixed(r["prep_s"].get<double>(), 2) << " s, table " << bench_fixed(r["table_mb"].get<double>(), 1)
      << " MB, peak RSS " << bench_fixed(r["peak_rss_mb"].get<double>(), 0) << " MB\n"
      << "  view  extract_ms  hidden_ms  points  polylines  length_mm\n";
  for (const auto& v : r["per_view"])
    out << "  " << std::setw(4) << bench_fixed(v["azimuth_deg"].get<double>(), 0) << std::setw(12)
        << bench_fixed(v["extract_ms"].get<double>(), 1) << std::setw(11)
        << bench_fixed(v["hidden_ms"].get<double>(), 1) << std::setw(8) << v["points"].get<std::size_t>()
        << std::setw(11) << v["polylines"].get<std::size_t>() << std::setw(11)
        << bench_fixed(v["length_mm"].get<double>(), 0) << "\n";
  out << "  median view " << bench_fixed(r["median_view_ms"].get<double>(), 1) << " ms (extract "
      << bench_fixed(r["median_extract_ms"].get<double>(), 1) << " + hidden "
      << bench_fixed(r["median_hidden_ms"].get<double>(), 1) << "), max "
      << bench_fixed(r["max_view_ms"].get<double>(), 1) << " ms; residuals |D-c|/range "
      << r["max_value_residual"].get<double>() << ", |G.V| " << r["max_dot_residual"].get<double>() << "\n";
  if (!r.contains("orbit_views")) return;
  out << "  orbit, 36 views 10 deg apart as the editor's live view (each from the previous one's curves, hidden cells "
         "seeding nothing, a 1280x720 screen's density)\n"
      << "  view  view_ms  points  visible  polylines  from_prev  coverage\n";
  for (const auto& v : r["orbit_views"])
    out << "  " << std::setw(4) << bench_fixed(v["azimuth_deg"].get<double>(), 0) << std::setw(9)
        << bench_fixed(v["view_ms"].get<double>(), 1) << std::setw(8) << v["points"].get<std::size_t>() << std::setw(9)
        << v["visible_points"].get<std::size_t>() << std::setw(11) << v["polylines"].get<std::size_t>() << std::setw(11)
        << v["traced_from_previous"].get<std::size_t>() << std::setw(9)
        << bench_fixed(100.0 * v["coverage"].get<double>(), 1) << "%\n";
  out << "  orbit median view " << bench_fixed(r["orbit_median_view_ms"].get<double>(), 1) << " ms, max "
      << bench_fixed(r["orbit_max_view_ms"].get<double>(), 1) << " ms; coverage of the complete extraction's visible "
      << "points " << bench_fixed(100.0 * r["orbit_median_coverage"].get<double>(), 1) << "% (median), "
      << bench_fixed(100.0 * r["orbit_min_coverage"].get<double>(), 1) << "% (worst view)\n";
}

// `trispline bench editor`: per scene the editor's and Blender's frame times, then the recording ratio.
void print_editor_bench_table(const nlohmann::json& r, std::ostream& out) {
  out << "editor frames (" << r["frames"].get<int>() << " idle, " << r["frames"].get<int>()
      << " orbiting 3 deg a frame), window " << r["window"].dump() << ", " << r.value("gl_renderer", "") << "\n"
      << "  scene     idle ms  orbit ms (median / p95)  Blender idle / orbit ms\n";
  for (const auto& s : r["scenes"]) {
    out << "  " << std::left << std::setw(8) << s["name"].get<std::string>() << std::right << std::setw(9)
        << bench_fixed(s["idle_median_ms"].get<double>(), 1) << std::setw(10)
        << bench_fixed(s["orbit_median_ms"].get<double>(), 1) << " / " << std::setw(7)
        << bench_fixed(s["orbit_p95_ms"].get<double>(), 1);
    if (s.contains("blender_redraw_ms"))
      out << std::setw(14) << bench_fixed(s["blender_redraw_ms"].get<double>(), 1) << " / "
          << bench_fixed(s["blender_orbit_median_ms"].get<double>(), 1);
    if (s.contains("silhouette_median_ms"))
      out << "  (silhouettes " << bench_fixed(s["silhouette_median_ms"].get<double>(), 0) << " ms each, "
          << s["silhouette_results"].get<std::size_t>() << " while orbiting)";
    out << "\n";
  }
  out << "  recording with a render-hidden volume: " << bench_fixed(r["record_hidden_volume_ratio"].get<double>(), 2)
      << "x the frame time without (" << bench_fixed(r["record_ms_per_frame"]["with_hidden_volume"].get<double>(), 0)
      << " / " << bench_fixed(r["record_ms_per_frame"]["without"].get<double>(), 0) << " ms)\n";
}

// `trispline bench bounds`: certificate times per lattice, then the soundness sweep's counts.
void print_bounds_table(const nlohmann::json& r, std::ostream& out) {
  out << "fold-free certificate, " << r["threads"].get<int>() << " threads\n"
      << "  order  controls   cells   quick  verdict          ms   exact ms (Bernstein boxes)\n";
  for (const auto& c : r["certificate"])
    out << "  " << std::setw(5) << c["order"].get<int>() << std::setw(8) << c["controls"].get<int>() << "^3"
        << std::setw(8) << c["cells"].get<std::size_t>() << std::setw(8) << c["quick_cells"].get<std::size_t>() << "  "
        << std::setw(10) << std::left << c["verdict"].get<std::string>() << std::right << std::setw(10)
        << bench_fixed(c["ms"].get<double>(), 2) << std::setw(11) << bench_fixed(c["exact_ms"].get<double>(), 2) << " ("
        << c["exact_boxes"].get<std::size_t>() << ")\n";
  const auto& w = r["sweep"];
  out << "  sweep: " << w["lattices"].get<int>() << " random lattices: " << w["fold_free"].get<std::size_t>()
      << " fold-free, " << w["fold"].get<std::size_t>() << " fold, " << w["undecided"].get<std::size_t>()
      << " undecided; sampling finds det J <= 0 in " << w["sampled_folds"].get<std::size_t>()
      << "; certified yet folded: " << w["certified_but_sampled_fold"].get<std::size_t>()
      << "; folds reported where det J > 0: " << w["fold_reported_at_positive_det"].get<std::size_t>() << "\n";
  const auto& t = r["triangles"];
  out << "per-triangle error bounds: " << t["triangles"].get<std::size_t>() << " triangles ("
      << t["vertices"].get<std::size_t>() << " vertices, " << t["mesh"]["source"].get<std::string>()
      << ") in a perturbed tri-cubic 8^3 lattice: " << bench_fixed(t["ms"].get<double>(), 1) << " ms (cell bounds "
      << bench_fixed(t["prepare_ms"].get<double>(), 2) << " ms), "
      << bench_fixed(t["per_second"].get<double>() / 1e6, 1) << " M triangles/s; bound median "
      << t["median_bound"].get<double>() << ", max " << t["max_bound"].get<double>() << " world units\n";
  const auto& s = r["soundness"];
  out << "bound soundness: " << s["triangles"].get<std::size_t>() << " triangles in "
      << s["lattices"].get<std::size_t>() << " random lattices (" << s["unbounded"].get<std::size_t>()
      << " unbounded), " << bench_fixed(s["ms"].get<double>() / 1000.0, 1) << " s\n"
      << "  method             exceeded   tightness median    worst\n";
  for (const auto& [name, m] : s["methods"].items())
    out << "  " << std::setw(18) << std::left << name << std::right << std::setw(9) << m["exceeded"].get<std::size_t>()
        << std::setw(19) << bench_fixed(m["tightness"]["median"].get<double>(), 2) << std::setw(9)
        << bench_fixed(m["tightness"]["worst"].get<double>(), 1) << "\n";
  out << "certified refinement of the seed's cube (triangles; the seed: midpoint " << r["refinement_seed"]["midpoint"]
      << ", greville " << r["refinement_seed"]["greville"] << ")\n"
      << "  deformation   tolerance  midpoint  greville      best  best/midpoint\n";
  for (const auto& row : r["refinement"])
    out << "  " << std::setw(12) << std::left << row["deformation"].get<std::string>() << std::right << std::setw(11)
        << row["tolerance"].get<double>() << std::setw(10) << row["midpoint"]["triangles"].get<std::size_t>()
        << std::setw(10) << row["greville"]["triangles"].get<std::size_t>() << std::setw(10)
        << row["best"]["triangles"].get<std::size_t>() << std::setw(13)
        << bench_fixed(100.0 * row["best_over_midpoint"].get<double>(), 0) << " %\n";
}

// A `trispline bench` subcommand: `name`, `description`, and --json (one JSON object instead of the table) into
// `json`.
CLI::App* bench_subcommand(CLI::App& bench, bool& json, const std::string& name, const std::string& description) {
  CLI::App* cmd = bench.add_subcommand(name, description);
  cmd->add_flag("--json", json, "Print one JSON object instead of a table");
  return cmd;
}

// `trispline bench ffd`: FFD throughput of every evaluator backend on a mesh's vertices.
void add_bench_ffd(CLI::App& bench, CliRequest& o) {
  o.ffd_cmd = bench_subcommand(
      bench, o.ffd.json, "ffd",
      "FFD throughput of every evaluator backend (CPU reference/fast, GLSL compute/vertex) on the bunny "
      "subdivided to ~0.8 M vertices, 4^3 and 8^3 lattices, orders 3 and 4");
  o.ffd_cmd
      ->add_option("--mesh", o.ffd.mesh_path,
                   "Benchmark this mesh's vertices instead (OBJ/PLY/OFF/STL/glTF; default: the bunny)")
      ->check(CLI::ExistingFile);
  o.ffd_cmd
      ->add_option("--subdiv", o.ffd.subdivision,
                   "OpenSubdiv bilinear subdivision levels (default 2 for the bunny, 0 for --mesh)")
      ->check(CLI::Range(0, 6));
  o.ffd_cmd->add_option("--runs", o.ffd.runs, "Timed runs per case; the median is reported")
      ->check(CLI::Range(1, 1000));
  o.ffd_cmd->add_flag("!--cpu-only", o.ffd.gpu, "Skip the GLSL backends (no GL context)");
  o.ffd_cmd
      ->add_option("--gpu-shaders", o.ffd.gpu_shaders,
                   "How GLSL shaders get the orders: auto (generic on software renderers), specialised, generic")
      ->check(CLI::IsMember({"auto", "specialised", "generic"}));
}

// `trispline bench place`: place.sketch end to end, ms per stage, with and without the mass-spring contact surface.
void add_bench_place(CLI::App& bench, CliRequest& o) {
  o.place_cmd = bench_subcommand(
      bench, o.place.json, "place",
      "place.sketch end to end (stroke -> placed bunny over the teapot and the terrain), ms per stage, "
      "mass-spring contact surface on and off");
  o.place_cmd->add_option("--runs", o.place.runs, "Timed runs per case after one warm-up; the median is reported")
      ->check(CLI::Range(1, 1000));
  o.place_cmd->add_option("--mesh", o.place.mesh_path, "Place this mesh instead of assets/data/bunny.obj")
      ->check(CLI::ExistingFile);
  o.place_cmd->add_option("--samples", o.place_samples, "Contact rays NU NV (default 64 8)")
      ->expected(2)
      ->check(CLI::Range(2, 4096));
  auto* on_only = o.place_cmd->add_flag("--springs", o.springs_on_only, "Only with the mass-spring contact surface");
  o.place_cmd->add_flag("--no-springs", o.springs_off_only, "Only without the mass-spring contact surface")
      ->excludes(on_only);
  o.place_cmd->add_option("--scene", o.place.scenes, "Scenes: teapot, terrain (default both)")
      ->check(CLI::IsMember({"teapot", "terrain"}));
}

// `trispline bench dffd`: discontinuous FFD per frame (split + cap + deform).
void add_bench_dffd(CLI::App& bench, CliRequest& o) {
  o.dffd_cmd = bench_subcommand(
      bench, o.dffd.json, "dffd",
      "Discontinuous FFD per frame: split + cap + deform of the bunny walking through bars (seed §6.3)");
  o.dffd_cmd->add_option("--scene", o.dffd.scene_path, "Scene log with an animated dffd.split object")
      ->default_str("assets/scenes/seed/bars_walk.jsonl");
  o.dffd_cmd->add_option("--runs", o.dffd.runs, "Timed evaluations per frame (median)")->check(CLI::PositiveNumber);
  o.dffd_cmd->add_option("--frames", o.dffd.frames, "Frames sampled over the walk")->check(CLI::PositiveNumber);
}

// `trispline bench ddm`: live DDM layers drawn by GPU instancing, GPU ms per frame.
void add_bench_ddm(CLI::App& bench, CliRequest& o) {
  o.ddm_cmd = bench_subcommand(
      bench, o.ddm.json, "ddm",
      "Live DDM layers drawn by GPU instancing: tile vertices, GPU ms per frame, fps (seed §5.3.2, Table 5.1)");
  o.ddm_cmd->add_option("--frames", o.ddm.frames, "Timed frames per case (after 2 warm-up frames)")
      ->check(CLI::PositiveNumber);
  o.ddm_cmd->add_option("--width", o.ddm.width, "Offscreen target width, pixels")->check(CLI::PositiveNumber);
  o.ddm_cmd->add_option("--height", o.ddm.height, "Offscreen target height, pixels")->check(CLI::PositiveNumber);
  o.ddm_cmd->add_option("--samples", o.ddm.samples, "MSAA samples")->check(CLI::Range(1, 16));
  o.ddm_cmd
      ->add_option("--case", o.ddm.cases,
                   "Cases: thorns_face, thorns_teapot, chains_1m, chains_3m, orbit_default, orbit_fine, follow_bunny "
                   "(default all)")
      ->check(CLI::IsMember(
          {"thorns_face", "thorns_teapot", "chains_1m", "chains_3m", "orbit_default", "orbit_fine", "follow_bunny"}));
  o.ddm_cmd->add_flag("!--no-cpu", o.ddm.cpu_reference, "Do not time the CPU reference evaluation");
}

// `trispline bench silhouettes`: silhouettes of a CT/MRI iso-surface, ms per view.
void add_bench_silhouettes(CLI::App& bench, CliRequest& o) {
  o.silhouettes_cmd =
      bench_subcommand(bench, o.silhouettes_json, "silhouettes",
                       "Silhouettes of a CT/MRI iso-surface (seed ch. 7): singleton preprocessing, then ms per view "
                       "around the volume (default: the Cranium CT at 226 HU, 36 views)");
  o.silhouettes_cmd
      ->add_option("--volume", o.silhouettes.volume_path,
                   "Volume file (NIfTI, DICOM folder, .inv3) or analytic:sphere|torus|sines")
      ->default_str("assets/data/Cranium.inv3");
  o.silhouettes_cmd->add_option("--iso", o.silhouettes.iso, "Iso-level, the volume's units (HU for CT)")
      ->default_str("226");
  o.silhouettes_cmd->add_option("--views", o.silhouettes.views, "Views evenly around the volume")
      ->check(CLI::Range(1, 100000));
  o.silhouettes_cmd->add_option("--order", o.silhouettes.order, "Spline order per axis (degree + 1)")
      ->check(CLI::Range(2, 4));
  o.silhouettes_cmd->add_option("--subdivision", o.silhouettes.subdivision, "Newton seeds per singleton axis")
      ->check(CLI::Range(1, 4));
  o.silhouettes_cmd->add_flag("!--no-hidden", o.silhouettes.hidden, "Skip the hidden-line test");
  o.silhouettes_cmd->add_flag("--orbit", o.silhouettes.orbit,
                              "Also orbit as the editor's live view does with hidden lines removed: 36 views 10 "
                              "degrees apart, each seeded from the previous one, checked against complete extractions");
  o.silhouettes_cmd->add_option("--views-out", o.silhouettes.views_out,
                                "Write the views' exact cameras (eye, target, up, fov, viewport; world mm) to this "
                                "JSON file, so that a peer renders the same views");
}

// `trispline bench editor`: the editor's frame times beside Blender's, and recording with a hidden volume.
void add_bench_editor(CLI::App& bench, CliRequest& o) {
  o.editor_bench_cmd = bench_subcommand(
      bench, o.editor_bench_json, "editor",
      "The editor's frame times (idle, orbiting) on the default scene, a tiled teapot and a volume with silhouettes, "
      "beside Blender's viewport redraw of the same meshes, and the cost of recording with a hidden volume (needs X: "
      "tests/with_xvfb.sh 1280x800x24 ...)");
  o.editor_bench_cmd->add_option("--frames", o.editor_bench.frames, "Idle and orbiting frames per scene")
      ->check(CLI::Range(1, 10000));
  o.editor_bench_cmd->add_option("--assets", o.editor_bench.assets, "The project's assets folder")
      ->capture_default_str();
  o.editor_bench_cmd->add_option("--volume", o.editor_bench.volume_path, "The volume scene's volume")
      ->capture_default_str();
  o.editor_bench_cmd->add_option("--iso", o.editor_bench.iso, "Its iso-level, the volume's units")
      ->capture_default_str();
  o.editor_bench_cmd->add_option("--work", o.editor_bench.work,
                                 "Folder for the logs, outputs and child logs (default: a new temporary folder)");
  o.editor_bench_cmd->add_flag("!--no-blender", o.editor_bench.blender, "Do not time Blender");
}

// `trispline bench bounds`: the fold-free certificate, per-triangle error bounds, certified refinement.
void add_bench_bounds(CLI::App& bench, CliRequest& o) {
  o.bounds_cmd = bench_subcommand(
      bench, o.bounds_json, "bounds",
      "Guarantees: the fold-free certificate's time on 4^3, 8^3, 16^3 lattices (orders 3, 4) and a soundness "
      "sweep over random lattices against dense sampling of det J; per-triangle error bounds on the 836K-vertex "
      "bunny, their soundness and tightness against the measured error, certified refinement of the seed's "
      "cube");
  o.bounds_cmd->add_option("--repeats", o.bounds.repeats, "Certificate timings: best of this many runs")
      ->check(CLI::Range(1, 1000));
  o.bounds_cmd->add_option("--lattices", o.bounds.lattices, "Random lattices in the soundness sweep")
      ->check(CLI::Range(0, 10000000));
  o.bounds_cmd
      ->add_option("--soundness-triangles", o.bounds.soundness_triangles,
                   "Triangles (of the bunny, in random lattices) whose bounds are checked against the measured "
                   "error")
      ->check(CLI::Range(0, 100000000));
}

// `trispline bench press`: a pressing drag on a ~1 M-vertex object.
void add_bench_press(CLI::App& bench, CliRequest& o) {
  o.press_cmd = bench_subcommand(
      bench, o.press.json, "press",
      "A pressing drag on a ~1 M-vertex object: Press tool per mouse move, pressed lattice, cpu_fast / GLSL "
      "re-evaluation per drag sample, and the lattice.press command at release");
  o.press_cmd
      ->add_option("--vertices", o.press.vertices,
                   "Target vertex count: the bunny's subdivision level closest to it (default 1000000)")
      ->check(CLI::Range(8, 100000000));
  o.press_cmd->add_option("--runs", o.press.runs, "Drags, timed updates and command runs (median)")
      ->check(CLI::Range(1, 1000));
  o.press_cmd->add_option("--mesh", o.press.mesh_path, "Use this mesh instead of assets/data/bunny.obj")
      ->check(CLI::ExistingFile);
  o.press_cmd->add_flag("!--cpu-only", o.press.gpu, "Skip glsl_compute (no GL context)");
}

// `trispline bench ffd|place|dffd|ddm|press|silhouettes|bounds`.
void add_bench(CLI::App& app, CliRequest& o) {
  auto* bench = app.add_subcommand("bench", "Benchmarks that print figures (never assert timings)");
  bench->require_subcommand(1);
  add_bench_ffd(*bench, o);
  add_bench_place(*bench, o);
  add_bench_dffd(*bench, o);
  add_bench_ddm(*bench, o);
  add_bench_silhouettes(*bench, o);
  add_bench_editor(*bench, o);
  add_bench_bounds(*bench, o);
  add_bench_press(*bench, o);
}

// `trispline commands [ID] [--docs FILE]`.
void add_commands(CLI::App& app, CliRequest& o) {
  o.commands_cmd = app.add_subcommand("commands", "List the commands a log may contain");
  o.commands_cmd->add_option("id", o.command_id, "Show this command's parameters as a Markdown table");
  o.commands_cmd->add_option(
      "--docs", o.docs_file,
      "Rewrite the generated parameter tables (<!-- params: ID --> blocks) of this Markdown file");
}

// Lists the commands, one command's parameters, or rewrites a Markdown file's generated tables.
int run_commands(const CliRequest& o) {
  const auto& registry = CommandRegistry::builtin();
  if (!o.docs_file.empty()) return rewrite_command_docs(o.docs_file, registry);
  if (!o.command_id.empty()) {
    const auto ids = registry.ids();
    if (std::find(ids.begin(), ids.end(), o.command_id) == ids.end()) {
      std::cerr << "trispline commands: no command '" << o.command_id << "' (trispline commands lists them)\n";
      return 2;
    }
    std::cout << "# " << o.command_id << "\n"
              << registry.summary(o.command_id) << "\n\n"
              << params_table(registry, o.command_id);
    return 0;
  }
  for (const auto& id : registry.ids()) std::cout << id << "\t" << registry.summary(id) << "\n";
  std::cout << "edit.undo\tUndo the last command\nedit.redo\tRedo the last undone command\n";
  return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"trispline — interactive modeling with trivariate B-spline functions"};
  app.require_subcommand(0, 1);
  CliRequest o;
  add_edit(app, o);
  add_replay(app, o);
  add_bench(app, o);
  add_commands(app, o);
  add_farm_commands(app, o.farm);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or the help); its own codes (104 conversion, 105 validation, …) become the documented
    // 2 for bad input, so scripts and the farm see one code for every bad value.
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    if (*o.replay_cmd) return run_replay(o.replay);
    if (*o.ffd_cmd) return run_bench_ffd(o.ffd, std::cout, std::cerr);
    if (*o.place_cmd) {
      o.place.samples_u = o.place_samples.at(0);
      o.place.samples_v = o.place_samples.at(1);
      o.place.springs = o.springs_on_only ? "on" : o.springs_off_only ? "off" : "both";
      return run_bench_place(o.place, std::cout, std::cerr);
    }
    if (*o.dffd_cmd) return run_bench_dffd(o.dffd, std::cout, std::cerr);
    if (*o.ddm_cmd) return run_bench_ddm(o.ddm, std::cout, std::cerr);
    if (*o.press_cmd) return run_bench_press(o.press, std::cout, std::cerr);
    if (*o.editor_bench_cmd)
      return bench_emit(run_editor_benchmark(o.editor_bench), o.editor_bench_json, std::cout, print_editor_bench_table);
    if (*o.silhouettes_cmd)
      return bench_emit(core::run_silhouette_benchmark(o.silhouettes), o.silhouettes_json, std::cout,
                        print_silhouette_table);
    if (*o.bounds_cmd)
      return bench_emit(core::run_bounds_benchmark(o.bounds), o.bounds_json, std::cout, print_bounds_table);
    if (*o.commands_cmd) return run_commands(o);
    if (const int farm = run_farm_command(o.farm); farm >= 0) return farm;
    if (!o.open_log.empty()) o.edit.open_log = o.open_log;
    return run_editor(o.edit);
  } catch (const std::exception& e) {
    std::cerr << "trispline: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace trispline::editor
