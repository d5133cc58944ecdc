#include "bench/bench_editor.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "editor/replay/process.h"

extern char** environ;

namespace trispline::editor {
namespace fs = std::filesystem;
namespace {

using json = nlohmann::json;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * double(v.size())))];
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("bench editor: " + path.string() + " was not written");
  return json::parse(in);
}

// The lines of a log with relative "path" fields made absolute (against the log's folder), so the log can be
// written elsewhere.
std::vector<json> absolute_log(const fs::path& log) {
  std::ifstream in(log);
  if (!in)
    throw std::runtime_error("bench editor: cannot read " + log.string() +
                             " (run from the project's folder, "
                             "or give --assets)");
  std::vector<json> lines;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    json j = json::parse(line);
    if (j.contains("path") && j["path"].is_string() && fs::path(j["path"].get<std::string>()).is_relative())
      j["path"] = fs::absolute(log.parent_path() / j["path"].get<std::string>()).lexically_normal().string();
    lines.push_back(std::move(j));
  }
  return lines;
}

void write_log(const fs::path& path, const std::vector<json>& lines) {
  std::ofstream out(path);
  for (const json& j : lines) out << j.dump() << '\n';
  if (!out) throw std::runtime_error("bench editor: cannot write " + path.string());
}

// Runs argv with its output into `log`; throws naming the log unless it exits with 0.
void run(const std::vector<std::string>& argv, const fs::path& log, const std::vector<std::string>* env = nullptr) {
  const pid_t pid = start_process(argv, log, env);
  if (const int status = wait_process(pid); status != 0)
    throw std::runtime_error("bench editor: `" + argv[0] + " " + (argv.size() > 1 ? argv[1] : "") + "` exited with " +
                             std::to_string(status) + "; see " + log.string());
}

// The environment of the editor's child processes: this process's, with TRISPLINE_STATE_DIR set to `state` (no
// session of the user's is touched).
std::vector<std::string> editor_bench_environment(const fs::path& state) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("TRISPLINE_STATE_DIR=", 0) != 0) env.emplace_back(*e);
  env.push_back("TRISPLINE_STATE_DIR=" + state.string());
  return env;
}

// One scene of the benchmark: its name and its command log (absolute paths).
struct EditorBenchScene {
  std::string name;
  std::vector<json> log;
};

// The scenes: "default" (the project's default scene), "tiles" (the teapot filled with thorns on auto UVs) and
// "volume" (`load`, its silhouettes with hidden lines removed).
std::vector<EditorBenchScene> editor_bench_scenes(const std::vector<json>& default_log, const json& load) {
  const json camera = {{"cmd", "camera.set"}, {"eye", {0.0, 1.6, 2.3}}, {"target", {0.0, 0.45, 0.0}},
                       {"up", {0, 1, 0}},     {"fov_deg", 38},          {"viewport", {1280, 720}}};
  const std::vector<json> tiles_log = {
      {{"cmd", "scene.primitive"}, {"kind", "teapot"}, {"name", "teapot"}, {"color", {0.86, 0.84, 0.80}}},
      camera,
      {{"cmd", "ddm.fill"},
       {"object", "teapot"},
       {"layer", "thorns"},
       {"tile", "thorn"},
       {"layout", "rect"},
       {"base", "auto_uv"},
       {"tile_size", 0.065},
       {"height", 0.05},
       {"color", {0.55, 0.62, 0.72}}}};
  const std::vector<json> volume_log = {
      load, {{"cmd", "volume.silhouettes"}, {"object", "volume"}, {"style", "plain"}, {"hidden", "remove"}}};
  return {{"default", default_log}, {"tiles", tiles_log}, {"volume", volume_log}};
}

// Scene `s` in the editor (`trispline edit --bench-out`): its row of idle and orbiting frame times (ms, median and
// p95), the viewport and, for the volume, the silhouette extractions while orbiting. Sets out["gl_renderer"].
json time_editor_scene(const fs::path& self, const fs::path& work, const std::vector<std::string>& env,
                       const EditorBenchOptions& o, const EditorBenchScene& s, json& out) {
  const fs::path log = work / (s.name + ".jsonl");
  write_log(log, s.log);
  const fs::path figures = work / (s.name + ".editor.json");
  fs::remove(figures);
  run({self.string(), "edit", "--no-recover", "--bench-out", figures.string(), "--bench-frames",
       std::to_string(o.frames), "--width", std::to_string(o.width), "--height", std::to_string(o.height),
       log.string()},
      work / (s.name + ".editor.log"), &env);
  const json e = read_json(figures);
  if (e.value("log_errors", 0) > 0)
    throw std::runtime_error("bench editor: the editor logged errors opening " + log.string() + "; see " +
                             (work / (s.name + ".editor.log")).string());
  const auto idle = e["idle_ms"].get<std::vector<double>>(), orbit = e["orbit_ms"].get<std::vector<double>>();
  json row = {{"name", s.name},
              {"idle_median_ms", quantile(idle, 0.5)},
              {"idle_p95_ms", quantile(idle, 0.95)},
              {"orbit_median_ms", quantile(orbit, 0.5)},
              {"orbit_p95_ms", quantile(orbit, 0.95)},
              {"viewport", e["viewport"]}};
  out["gl_renderer"] = e["gl_renderer"];
  if (s.name == "volume") {
    const auto sil = e["silhouette_ms"].get<std::vector<double>>();
    row["silhouette_results"] = sil.size();
    row["silhouette_median_ms"] = quantile(sil, 0.5);
  }
  return row;
}

// The same meshes for Blender (scripts/blender_redraw_timer.py): the replayed scene.glb; for the volume its
// iso-surface as a mesh. Its redraw and orbit times (ms) and vertices go to `row`, its version to
// out["blender_version"].
void time_blender_scene(const fs::path& self, const fs::path& work, const EditorBenchOptions& o,
                        const EditorBenchScene& s, json& row, json& out) {
  std::vector<json> blog = s.log;
  if (s.name == "volume")
    blog.push_back({{"cmd", "volume.export"}, {"object", "volume"}, {"what", "iso"}, {"path", "iso.glb"}});
  const fs::path blender_log = work / (s.name + ".blender.jsonl"), dir = work / (s.name + ".replay");
  write_log(blender_log, blog);
  run({self.string(), "replay", blender_log.string(), "--out", dir.string()}, work / (s.name + ".replay.log"));
  const fs::path glb = dir / (s.name == "volume" ? "iso.glb" : "scene.glb");
  const fs::path bfig = work / (s.name + ".blender.json");
  fs::remove(bfig);
  const fs::path script = o.assets / ".." / "scripts" / "blender_redraw_timer.py";
  run({"blender", "--factory-startup", "--window-geometry", "0", "0", std::to_string(o.width), std::to_string(o.height),
       "--python", script.string(), "--", "--glb", glb.string(), "--frames", std::to_string(o.frames), "--orbit-deg",
       "3", "--out", bfig.string()},
      work / (s.name + ".blender.log"));
  const json b = read_json(bfig);
  if (b.contains("error")) throw std::runtime_error("bench editor: Blender: " + b["error"].get<std::string>());
  row["blender_redraw_ms"] = b["idle_median_ms"];
  row["blender_orbit_median_ms"] = b["orbit_median_ms"];
  row["blender_orbit_p95_ms"] = b["orbit_p95_ms"];
  row["blender_vertices"] = b["vertices"];
  row["blender_viewport"] = b["viewport"];
  out["blender_version"] = b["blender_version"];
}

// Recording with a render-hidden volume: anim.record (640 × 360, `record_frames` frames) of the default scene
// replayed without and with `load` hidden from renders. Sets out["record_ms_per_frame"] (ms a written frame) and
// out["record_hidden_volume_ratio"] (with ÷ without).
void time_hidden_volume_recording(const fs::path& self, const fs::path& work, const EditorBenchOptions& o,
                                  const std::vector<json>& default_log, const json& load, json& out) {
  const json record = {{"cmd", "anim.record"}, {"frames", {1, o.record_frames}},
                       {"width", 640},         {"height", 360},
                       {"glb", false},         {"mp4", false}};
  double per_frame[2] = {0.0, 0.0};
  for (int with = 0; with < 2; ++with) {
    std::vector<json> log = default_log;
    if (with) {
      log.push_back(load);
      log.push_back({{"cmd", "object.visibility"}, {"object", "volume"}, {"render", false}});
    }
    log.push_back(record);
    const std::string name = with ? "record_hidden_volume" : "record";
    write_log(work / (name + ".jsonl"), log);
    run({self.string(), "replay", (work / (name + ".jsonl")).string(), "--out", (work / name).string()},
        work / (name + ".log"));
    const json r = read_json(work / name / "report.json");
    per_frame[with] = r["record"]["ms"].get<double>() / std::max(1, r["record"]["frames_written"].get<int>());
  }
  out["record_ms_per_frame"] = {{"without", per_frame[0]}, {"with_hidden_volume", per_frame[1]}};
  out["record_hidden_volume_ratio"] = per_frame[1] / per_frame[0];
}

}  // namespace

json run_editor_benchmark(const EditorBenchOptions& o) {
  if (o.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw std::runtime_error(
        "bench editor opens the editor's window: run it under X, e.g. `tests/with_xvfb.sh 1280x800x24 trispline "
        "bench editor`");
  const fs::path self = fs::read_symlink("/proc/self/exe");
  const fs::path work =
      o.work.empty() ? fs::temp_directory_path() / ("trispline-bench-editor-" + std::to_string(getpid())) : o.work;
  fs::create_directories(work / "state");
  const std::vector<std::string> env = editor_bench_environment(work / "state");

  // The scenes' logs, with absolute paths.
  const std::vector<json> default_log = absolute_log(o.assets / "scenes" / "default.jsonl");
  const std::string volume = fs::absolute(o.volume_path).lexically_normal().string();
  const json load = {{"cmd", "volume.load"}, {"path", volume}, {"name", "volume"}, {"iso", o.iso}};
  const std::vector<EditorBenchScene> scenes = editor_bench_scenes(default_log, load);

  json out = {{"bench", "editor"}, {"frames", o.frames}, {"window", {o.width, o.height}}, {"work", work.string()}};
  json rows = json::array();
  for (const EditorBenchScene& s : scenes) {
    json row = time_editor_scene(self, work, env, o, s, out);
    if (o.blender) time_blender_scene(self, work, o, s, row, out);
    rows.push_back(row);
  }
  out["scenes"] = rows;

  time_hidden_volume_recording(self, work, o, default_log, load, out);
  return out;
}

}  // namespace trispline::editor
