#include "editor/replay/replay.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include "core/commands/anim_record.h"
#include "core/commands/file_output.h"
#include "core/image/image_io.h"
#include "core/mesh/gltf_io.h"
#include "core/scene/scene_export.h"
#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"
#include "editor/replay/elapsed.h"
#include "editor/replay/record.h"
#include "editor/replay/render_scene.h"
#include "ui/frame_timings.h"

namespace trispline::editor {
namespace {

nlohmann::json record_json(const ExecutionRecord& r, int line) {
  nlohmann::json j = {{"line", line}, {"cmd", r.cmd}, {"ok", r.ok}, {"ms", r.milliseconds}};
  if (!r.ok) j["error"] = r.error;
  if (!r.stats.empty()) j["stats"] = r.stats;
  return j;
}

// A measurement in ms, or null when it was not measured (negative) or is not finite.
nlohmann::json ms_or_null(double ms) { return ms >= 0 && std::isfinite(ms) ? nlohmann::json(ms) : nlohmann::json(); }

// timings.commands: every executed command's wall time and CPU time per stage (from its stats()).
nlohmann::json command_timings(const std::vector<ExecutionRecord>& records) {
  nlohmann::json out = nlohmann::json::array();
  for (const ExecutionRecord& r : records) {
    if (r.cmd.empty()) continue;  // a line that did not parse
    nlohmann::json stages = nlohmann::json::object();
    for (const ui::StageTiming& st : ui::stage_timings(r.stats)) stages[st.name] = st.ms;
    out.push_back(
        {{"line", r.log_line}, {"cmd", r.cmd}, {"ok", r.ok}, {"total_ms", r.milliseconds}, {"stages_ms", stages}});
  }
  return out;
}

nlohmann::json render_timings(const RenderedImage& image, const ReplayOptions& options) {
  const RenderTimings& t = image.timings;
  ui::PassTimings passes;
  passes.ffd_ms = t.ffd_ms;
  passes.draw_ms = t.draw_ms;
  passes.ffd_in_draw = t.ffd_in_draw;
  const double rate = ui::vertices_per_second(t.ffd_vertices, ui::ffd_time_ms(passes));
  return {{"ffd_backend", core::to_string(options.ffd_backend)},
          {"ffd_backend_label", ui::ffd_backend_label(options.ffd_backend)},
          {"renderer", image.renderer},
          {"timer_mode", t.timer_mode},
          {"time_s", options.time_s},
          {"ffd_objects", t.ffd_objects},
          {"ffd_vertices", t.ffd_vertices},
          {"ffd_ms", ms_or_null(t.ffd_ms)},
          {"draw_ms", ms_or_null(t.draw_ms)},
          {"ffd_in_draw", t.ffd_in_draw},
          {"volumes", t.volumes},
          {"volume_ms", ms_or_null(t.volume_ms)},
          {"silhouette_points", t.silhouettes},
          {"silhouette_ms", t.silhouette_ms},
          {"vertices_per_second", rate >= 0 ? nlohmann::json(rate) : nlohmann::json()}};
}

// Writes report.json whole or not at all (PATH.tmp, then rename): text that is not valid UTF-8 (a message quoting a
// hostile file) is replaced by U+FFFD rather than failing the dump, so a report is never empty.
bool write_report(const std::filesystem::path& path, const nlohmann::json& report) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  try {
    const std::string text = report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out << text;
      out.flush();
      if (!out) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, path);
    return true;
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    std::cerr << "cannot write " << path.string() << ": " << e.what() << "\n";
    return false;
  }
}

struct PendingRecording {
  int line = 0;
  core::Scene scene;  // as it was right after the anim.record line
  core::RecordRequest request;
};

RecordResult record_into(const core::Scene& scene, RecordOptions ro) {
  ro.ffd_backend = core::FfdBackend::cpu_ref;  // frames are the authoritative geometry, bit-exact
  RecordResult r = record_frames(scene, ro);
  std::cout << "recorded:       frames " << r.frame_first << "-" << r.frame_last << " (" << r.frames_written << ") in "
            << ro.out_dir.string() << "\n";
  if (!r.mp4_note.empty()) std::cout << "mp4:            " << r.mp4_note << "\n";
  return r;
}

// --frames, or the log's anim.record lines: writes report["record"] (and "records"); returns the new exit code.
int run_recordings(const core::Scene& scene, const std::vector<PendingRecording>& pending, const ReplayOptions& options,
                   nlohmann::json& report, int exit_code) {
  try {
    if (options.frames_given) {
      RecordOptions ro = options.frames;
      ro.out_dir = options.out_dir;
      ro.width = options.width;
      ro.height = options.height;
      ro.mp4 = false;
      report["record"] = record_into(scene, ro).to_json();
      return exit_code;
    }
    nlohmann::json all = nlohmann::json::array();
    for (const PendingRecording& p : pending) {
      // Headless replay writes under --out; the line's "out" was the editor's.
      nlohmann::json j = record_into(p.scene, record_options(p.request, options.out_dir)).to_json();
      j["line"] = p.line;
      all.push_back(j);
    }
    if (!all.empty()) report["record"] = all.back();
    if (all.size() > 1) report["records"] = all;
  } catch (const std::exception& e) {
    std::cerr << "cannot record frames: " << e.what() << "\n";
    report["record_error"] = e.what();
    return exit_code ? exit_code : 3;
  }
  return exit_code;
}

}  // namespace

ReplayResult replay_lines(History& history, const std::filesystem::path& log_path, const ReplayHook& on_executed,
                          const std::filesystem::path& output_dir, FileWrites writes) {
  ReplayResult result;
  std::vector<LogLine> lines;
  try {
    lines = read_log_text(log_path);
  } catch (const LogError& e) {
    result.ok = false;
    result.error = e.what();
    result.failed_line = e.line();
    return result;
  }
  core::CommandContext ctx;
  ctx.base_dir = log_path.has_parent_path() ? log_path.parent_path() : std::filesystem::path(".");
  ctx.output_dir = output_dir;
  const auto& registry = CommandRegistry::builtin();
  for (auto& line : lines) {
    try {
      parse_log_line(log_path, line);
    } catch (const LogError& e) {
      result.ok = false;
      result.error = e.what();
      result.failed_line = line.number;
      ExecutionRecord bad;
      bad.ok = false;
      bad.error = e.what();
      bad.log_line = line.number;
      result.records.push_back(bad);
      break;
    }
    ExecutionRecord rec;
    rec.line = line.json;
    rec.log_line = line.number;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      const auto cmd_it = line.json.find("cmd");
      const std::string id = cmd_it != line.json.end() && cmd_it->is_string() ? cmd_it->get<std::string>() : "";
      rec.cmd = id;
      if (id == "edit.undo" || id == "edit.redo") {
        const bool undo = id == "edit.undo";
        if (undo ? !history.can_undo() : !history.can_redo())
          throw core::CommandError(std::string("nothing to ") + (undo ? "undo" : "redo"), "cmd");
        undo ? history.undo() : history.redo();
        rec.milliseconds = ms_since(t0);
      } else {
        core::CommandPtr cmd = registry.parse(line.json, ctx);
        if (core::FileOutput* out = core::file_output(*cmd)) out->set_writes_files(writes == FileWrites::write);
        rec = history.execute(std::move(cmd));
        rec.log_line = line.number;
        if (on_executed) on_executed(history.last_executed(), line.number);
      }
    } catch (const core::CommandError& e) {
      rec.ok = false;
      rec.error = LogError(log_path, line.number, e.field(), e.what()).what();
      rec.milliseconds = ms_since(t0);
    } catch (const std::exception& e) {  // defensive: commands should only throw CommandError
      rec.ok = false;
      rec.error = LogError(log_path, line.number, "", e.what()).what();
      rec.milliseconds = ms_since(t0);
    }
    result.records.push_back(rec);
    if (!rec.ok) {
      result.ok = false;
      result.error = rec.error;
      result.failed_line = line.number;
      break;
    }
  }
  return result;
}

std::optional<std::pair<int, int>> parse_frame_range(const std::string& text) {
  auto number = [](const std::string& t) -> std::optional<int> {
    if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    return std::stoi(t);
  };
  const std::size_t dash = text.find('-');
  const auto a = number(text.substr(0, dash));
  const auto b = dash == std::string::npos ? a : number(text.substr(dash + 1));
  if (!a || !b || *a > *b) return std::nullopt;
  return std::make_pair(*a, *b);
}

int run_replay(const ReplayOptions& options) {
  core::Scene scene;
  History history(scene);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<PendingRecording> pending;  // the log's anim.record lines, with the scene as it was at each
  const ReplayHook hook = [&](const core::Command& command, int line) {
    if (options.frames_given || options.out_dir.empty()) return;
    if (const auto* rec = dynamic_cast<const core::AnimRecordCommand*>(&command); rec && rec->writes_files())
      pending.push_back({line, scene, rec->request()});
  };
  ReplayResult result = replay_lines(history, options.log, hook, options.out_dir);
  const double replay_ms = ms_since(t0);
  if (result.ok && options.frames_given) {
    std::string err = core::frame_range_error(scene.timeline, options.frames.frame_first, options.frames.frame_last);
    if (err.empty() && options.frames.piece_base >= 0 &&
        (options.frames.piece_base < scene.timeline.frame_start ||
         options.frames.piece_base > options.frames.frame_first))
      err = "--piece-base " + std::to_string(options.frames.piece_base) + " is not in [" +
            std::to_string(scene.timeline.frame_start) + ", " + std::to_string(options.frames.frame_first) + "]";
    if (!err.empty()) {
      std::cerr << "replay: --frames " << options.frames.frame_first << "-" << options.frames.frame_last << ": " << err
                << " (nothing written)\n";
      return 2;
    }
  }

  nlohmann::json report = {{"log", options.log.string()}, {"ok", result.ok}, {"replay_ms", replay_ms}};
  if (!result.ok) {
    report["error"] = result.error;
    report["failed_line"] = result.failed_line;
  }
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& r : result.records) lines.push_back(record_json(r, r.log_line));
  report["commands"] = lines;
  nlohmann::json objects = nlohmann::json::array();
  for (const auto& o : scene.objects())
    objects.push_back({{"name", o.name},
                       {"vertices", o.world_mesh ? o.world_mesh->vertex_count() : 0},
                       {"triangles", o.world_mesh ? o.world_mesh->triangle_count() : 0},
                       {"deformed", o.ffd != nullptr}});
  report["objects"] = objects;

  int exit_code = result.ok ? 0 : 2;
  if (!result.ok) std::cerr << "replay failed: " << result.error << "\n";

  report["ffd_backend"] = core::to_string(options.ffd_backend);
  report["time_s"] = options.time_s;
  nlohmann::json timings = {{"commands", command_timings(result.records)}};

  if (!options.out_dir.empty()) {
    std::filesystem::create_directories(options.out_dir);
    const auto glb = options.out_dir / "scene.glb";
    const auto png = options.out_dir / "final.png";
    // The exported geometry: the CPU reference at the requested time (authoritative), or, with another backend,
    // what that backend computes (read back from the GPU for GLSL backends).
    std::optional<core::Scene> exported;
    try {
      if (options.ffd_backend == core::FfdBackend::cpu_ref) {
        exported = options.time_s != 0 ? core::scene_at_time(scene, options.time_s) : scene;
        timings["geometry"] = {{"source", "cpu_ref"}};
      } else {
        BackendGeometry g = evaluate_with_backend(scene, options.ffd_backend, options.time_s);
        // ms includes building shader programs and reading back: a check of the path, not a throughput figure.
        timings["geometry"] = {{"source", core::to_string(options.ffd_backend)},
                               {"objects", g.objects},
                               {"vertices", g.vertices},
                               {"ms", g.ms}};
        if (!g.renderer.empty()) timings["geometry"]["renderer"] = g.renderer;
        exported = std::move(g.scene);
      }
    } catch (const std::exception& e) {
      std::cerr << "cannot evaluate the scene with FFD backend " << core::to_string(options.ffd_backend) << ": "
                << e.what() << "\n";
      report["scene_glb_error"] = std::string("FFD backend ") + core::to_string(options.ffd_backend) + ": " + e.what();
      exit_code = exit_code ? exit_code : 3;
    }
    if (exported) {
      try {
        const core::SceneExport nodes = core::scene_export_nodes(*exported);  // objects and live tile layers
        core::write_glb(glb, nodes.nodes);
        report["scene_glb"] = glb.string();
      } catch (const std::exception& e) {
        std::cerr << "cannot write " << glb << ": " << e.what() << "\n";
        report["scene_glb_error"] = e.what();
        exit_code = exit_code ? exit_code : 3;
      }
    }
    if (options.render) {
      try {
        const auto tr = std::chrono::steady_clock::now();
        const RenderSettings settings{options.ffd_backend, options.time_s};
        RenderedImage image = render_scene_headless(scene, options.width, options.height, settings);
        core::write_image_rgba8(png, image.width, image.height, image.rgba);
        report["final_png"] = png.string();
        report["renderer"] = image.renderer;
        report["render_ms"] = ms_since(tr);
        timings["render"] = render_timings(image, options);
      } catch (const std::exception& e) {
        std::cerr << "cannot render " << png << ": " << e.what() << "\n";
        report["final_png_error"] = e.what();
        exit_code = exit_code ? exit_code : 3;
      }
    }
    if (result.ok) exit_code = run_recordings(scene, pending, options, report, exit_code);
    report["timings"] = timings;
    const auto report_path = options.out_dir / "report.json";
    if (!write_report(report_path, report)) exit_code = exit_code ? exit_code : 3;
    if (report.contains("final_png")) std::cout << "rendered image: " << png.string() << "\n";
    if (report.contains("scene_glb")) std::cout << "exported scene: " << glb.string() << "\n";
    std::cout << "report:         " << report_path.string() << "\n";
  }
  return exit_code;
}

}  // namespace trispline::editor
