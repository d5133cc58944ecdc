#include "editor/replay.h"

#include "core/mesh/gltf_io.h"
#include "core/mesh/image_io.h"
#include "editor/command_log.h"
#include "editor/command_registry.h"
#include "editor/render_scene.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

namespace trispline::editor {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json record_json(const ExecutionRecord& r, int line) {
  nlohmann::json j = {{"line", line}, {"cmd", r.cmd}, {"ok", r.ok}, {"ms", r.milliseconds}};
  if (!r.ok) j["error"] = r.error;
  if (!r.stats.empty()) j["stats"] = r.stats;
  return j;
}

}  // namespace

ReplayResult replay_lines(History& history, const std::filesystem::path& log_path) {
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
        rec = history.execute(registry.parse(line.json, ctx));
        rec.log_line = line.number;
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

int run_replay(const ReplayOptions& options) {
  core::Scene scene;
  History history(scene);
  const auto t0 = std::chrono::steady_clock::now();
  ReplayResult result = replay_lines(history, options.log);
  const double replay_ms = ms_since(t0);

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

  if (!options.out_dir.empty()) {
    std::filesystem::create_directories(options.out_dir);
    const auto glb = options.out_dir / "scene.glb";
    const auto png = options.out_dir / "final.png";
    try {
      std::vector<core::GltfNode> nodes;
      for (const auto& o : scene.objects())
        if (o.world_mesh) nodes.push_back({o.name, o.world_mesh.get(), o.color});
      core::write_glb(glb, nodes);
      report["scene_glb"] = glb.string();
    } catch (const std::exception& e) {
      std::cerr << "cannot write " << glb << ": " << e.what() << "\n";
      report["scene_glb_error"] = e.what();
      exit_code = exit_code ? exit_code : 3;
    }
    if (options.render) {
      try {
        const auto tr = std::chrono::steady_clock::now();
        RenderedImage image = render_scene_headless(scene, options.width, options.height);
        core::write_image_rgba8(png, image.width, image.height, image.rgba);
        report["final_png"] = png.string();
        report["renderer"] = image.renderer;
        report["render_ms"] = ms_since(tr);
      } catch (const std::exception& e) {
        std::cerr << "cannot render " << png << ": " << e.what() << "\n";
        report["final_png_error"] = e.what();
        exit_code = exit_code ? exit_code : 3;
      }
    }
    const auto report_path = options.out_dir / "report.json";
    std::ofstream(report_path) << report.dump(2) << "\n";
    if (report.contains("final_png")) std::cout << "rendered image: " << png.string() << "\n";
    if (report.contains("scene_glb")) std::cout << "exported scene: " << glb.string() << "\n";
    std::cout << "report:         " << report_path.string() << "\n";
  }
  return exit_code;
}

}  // namespace trispline::editor
