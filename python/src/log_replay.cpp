#include "python/src/log_replay.h"

#include <chrono>
#include <fstream>

#include "core/commands/file_output.h"
#include "core/mesh/gltf_io.h"
#include "core/scene/scene_export.h"
#include "editor/commands/command_log.h"

namespace trispline::python {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void fail(LogRun& run, nlohmann::json& entry, const editor::LogError& e) {
  run.ok = false;
  run.error = e.what();
  run.field = e.field();
  run.failed_line = e.line();
  entry["ok"] = false;
  entry["error"] = run.error;
  run.commands.push_back(entry);
}

// One line: parsed, run, its report entry appended. False when it failed (run holds why).
bool run_line(PyScene& scene, const std::filesystem::path& log, editor::LogLine& line, const core::CommandContext& ctx,
              bool write_files, LogRun& run) {
  nlohmann::json entry = {{"line", line.number}, {"cmd", ""}, {"ok", true}, {"ms", 0.0}};
  const auto t0 = std::chrono::steady_clock::now();
  try {
    editor::parse_log_line(log, line);
    const auto it = line.json.find("cmd");
    if (it != line.json.end() && it->is_string()) entry["cmd"] = *it;
    if (entry["cmd"] == "anim.record") run.records = true;
    nlohmann::json done;
    if (entry["cmd"] == "edit.undo" || entry["cmd"] == "edit.redo") {
      done = scene.run(line.json, ctx);
    } else {
      core::CommandPtr cmd = parse_command(line.json, ctx);
      if (core::FileOutput* out = core::file_output(*cmd)) out->set_writes_files(write_files);
      done = scene.execute(std::move(cmd));
    }
    entry["ms"] = done["ms"];
    if (!done["stats"].empty()) entry["stats"] = done["stats"];
  } catch (const editor::LogError& e) {
    fail(run, entry, e);
    return false;
  } catch (const core::CommandError& e) {
    fail(run, entry, editor::LogError(log, line.number, e.field(), e.what()));
    return false;
  } catch (const std::exception& e) {  // defensive: commands throw CommandError
    fail(run, entry, editor::LogError(log, line.number, "", e.what()));
    return false;
  }
  if (entry["ms"] == 0.0) entry["ms"] = ms_since(t0);
  run.commands.push_back(entry);
  return true;
}

void write_text_atomic(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

LogRun run_log(PyScene& scene, const std::filesystem::path& log, const std::filesystem::path& output_dir,
               bool write_files) {
  LogRun run;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<editor::LogLine> lines;
  try {
    lines = editor::read_log_text(log);
  } catch (const editor::LogError& e) {
    nlohmann::json entry = {{"line", e.line()}, {"cmd", ""}, {"ok", false}, {"ms", 0.0}};
    fail(run, entry, e);
    return run;
  }
  core::CommandContext ctx;
  ctx.base_dir = log.has_parent_path() ? log.parent_path() : std::filesystem::path(".");
  ctx.output_dir = output_dir;
  for (editor::LogLine& line : lines)
    if (!run_line(scene, log, line, ctx, write_files, run)) break;
  run.ms = ms_since(t0);
  return run;
}

nlohmann::json replay_log(const std::filesystem::path& log, const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  PyScene scene;
  const LogRun run = run_log(scene, log, std::filesystem::absolute(out_dir), true);
  nlohmann::json report = {{"log", log.string()}, {"ok", run.ok}, {"replay_ms", run.ms}};
  if (!run.ok) {
    report["error"] = run.error;
    report["failed_line"] = run.failed_line;
  }
  report["commands"] = run.commands;
  nlohmann::json objects = nlohmann::json::array();
  for (const auto& o : scene.scene().objects())
    objects.push_back({{"name", o.name},
                       {"vertices", o.world_mesh ? o.world_mesh->vertex_count() : 0},
                       {"triangles", o.world_mesh ? o.world_mesh->triangle_count() : 0},
                       {"deformed", o.ffd != nullptr}});
  report["objects"] = objects;
  report["ffd_backend"] = "cpu_ref";
  report["time_s"] = 0.0;
  const std::filesystem::path glb = out_dir / "scene.glb";
  try {
    core::write_glb(glb, core::scene_export_nodes(scene.scene()).nodes);
    report["scene_glb"] = glb.string();
  } catch (const std::exception& e) {
    report["scene_glb_error"] = e.what();
  }
  report["final_png_error"] = "not rendered: the Python module has no GPU layer (`trispline replay` renders it)";
  if (run.records) report["record_error"] = "anim.record: recordings need the GPU layer (`trispline replay`)";
  write_text_atomic(out_dir / "report.json",
                    report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return report;
}

}  // namespace trispline::python
