// `trispline bench place`: placement end to end through the command path, per stage. See bench_place.h.
#include "bench/bench_place.h"

#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "ui/frame_timings.h"

namespace trispline::editor {

int bench_emit(const nlohmann::json& result, bool as_json, std::ostream& out,
               void (*table)(const nlohmann::json&, std::ostream&)) {
  if (as_json)
    out << result.dump() << "\n";
  else
    table(result, out);
  return 0;
}

double bench_median(std::vector<double> v) {
  if (v.empty()) throw std::invalid_argument("bench_median: no values");
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double bench_ms(const std::function<void()>& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string bench_fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

namespace {

using nlohmann::json;

// The scene set-up lines and the place.sketch line of one benchmark scene (see bench_place.h for the sources).
struct PlaceScene {
  std::vector<json> setup;  // scene, camera (the object is added separately)
  json place;               // without "samples" / "springs"
};

// A benchmark scene is a shipped log's set-up (its scene.primitive and camera.set lines) and its place.sketch line,
// laid on the bunny (length along x, up along y). Logs are read from the repository root, as the other benchmarks.
PlaceScene scene_lines(const std::string& name) {
  static const std::map<std::string, std::filesystem::path> kLogs = {
      {"teapot", "assets/scenes/default.jsonl"}, {"terrain", "tests/logs/real_mesh_on_terrain.jsonl"}};
  const auto log = kLogs.find(name);
  if (log == kLogs.end())
    throw std::invalid_argument("bench place: unknown scene '" + name + "' (use teapot or terrain)");
  std::ifstream in(log->second);
  if (!in)
    throw std::runtime_error("bench place: cannot read " + log->second.string() + " (run from the repository root)");
  PlaceScene s;
  for (std::string text; std::getline(in, text);) {
    if (text.empty() || text[0] == '#') continue;
    json line = json::parse(text);
    const std::string cmd = line.value("cmd", "");
    if (cmd == "scene.primitive" || cmd == "camera.set") s.setup.push_back(std::move(line));
    if (cmd == "place.sketch") s.place = std::move(line);
  }
  if (s.place.is_null()) throw std::runtime_error("bench place: " + log->second.string() + " has no place.sketch line");
  s.place.erase("samples");
  s.place["object"] = "bunny";
  s.place["length_axis"] = "x";
  s.place["up_axis"] = "y";
  return s;
}

// tests/logs/bridge_springs.jsonl's relaxation settings.
const json kSprings = {{"stiffness", 100}, {"damping", 30}, {"threshold_deg", 5}, {"max_steps", 5000}};

}  // namespace

std::vector<json> bench_place_scene(const std::string& name) {
  PlaceScene s = scene_lines(name);
  s.setup.push_back(s.place);
  return s.setup;
}

namespace {

ExecutionRecord execute(History& history, const json& line) {
  core::CommandContext ctx;
  try {
    return history.execute(CommandRegistry::builtin().parse(line, ctx));
  } catch (const core::CommandError& e) {
    throw std::runtime_error("bench: " + line.value("cmd", std::string("?")) + " failed: " + e.what());
  }
}

void print_place_table(const json& r, std::ostream& os) {
  const json& m = r.at("mesh");
  os << "place.sketch end to end on " << r.at("cpu").get<std::string>() << " (" << r.at("threads") << " threads)\n"
     << "object: " << m.at("source").get<std::string>() << ", " << m.at("vertices") << " vertices; contact rays "
     << r.at("samples")[0] << "x" << r.at("samples")[1] << "; median of " << r.at("runs")
     << " runs (after one warm-up), ms\n\n";
  if (m.at("fallback").get<bool>()) os << "NOTE: " << m.at("note").get<std::string>() << "\n\n";
  const json& cases = r.at("cases");
  os << std::left << std::setw(22) << "stage";
  for (const json& c : cases)
    os << std::right << std::setw(18)
       << (c.at("scene").get<std::string>() + (c.at("springs").get<bool>() ? "+springs" : ""));
  os << "\n";
  std::vector<std::string> stages;  // pipeline order; a stage only some cases have goes where it first appears
  for (const json& c : cases) {
    auto at = stages.begin();
    for (const json& name : c.at("stages")) {
      const auto found = std::find(stages.begin(), stages.end(), name.get<std::string>());
      at = found != stages.end() ? found + 1 : stages.insert(at, name.get<std::string>()) + 1;
    }
  }
  auto row = [&](const std::string& label, const std::function<std::string(const json&)>& cell) {
    os << std::left << std::setw(22) << label;
    for (const json& c : cases) os << std::right << std::setw(18) << cell(c);
    os << "\n";
  };
  for (const std::string& s : stages)
    row(s, [&](const json& c) {
      const json& ms = c.at("median_ms");
      return ms.contains(s) ? bench_fixed(ms.at(s).get<double>(), 2) : std::string("-");
    });
  row("total min..max", [](const json& c) {
    return bench_fixed(c.at("min_total_ms").get<double>(), 1) + ".." +
           bench_fixed(c.at("max_total_ms").get<double>(), 1);
  });
  row("warm-up total", [](const json& c) { return bench_fixed(c.at("warmup_ms").get<double>(), 1); });
  row("rays hit / total", [](const json& c) {
    return std::to_string(c.at("rays_hit").get<int>()) + "/" + std::to_string(c.at("rays_total").get<int>());
  });
  row("spring steps", [](const json& c) {
    return c.at("springs").get<bool>() ? std::to_string(c.at("springs_steps").get<int>()) +
                                             (c.at("springs_converged").get<bool>() ? " (conv.)" : " (cap)")
                                       : std::string("-");
  });
  row("scene vertices", [](const json& c) { return std::to_string(c.at("scene_vertices").get<std::size_t>()); });
  os << "\nstages: place.sketch stats (bvh_ms, ms.*, evaluate_ms = cpu_ref positions+normals); total = the command's "
        "wall time\nas History records it; other = total - stages (snapshot, rest mesh transform).\n";
}

}  // namespace

int run_bench_place(const BenchPlaceOptions& o, std::ostream& out, std::ostream& err) {
  if (o.runs < 1) throw std::invalid_argument("bench place: --runs must be >= 1");
  if (o.samples_u < 2 || o.samples_v < 2) throw std::invalid_argument("bench place: --samples must be >= 2 each");
  if (o.springs != "on" && o.springs != "off" && o.springs != "both")
    throw std::invalid_argument("bench place: springs must be on, off or both");
  if (o.scenes.empty()) throw std::invalid_argument("bench place: no scene");
  for (const std::string& s : o.scenes) scene_lines(s);  // validates the names before any work

  const std::string path = o.mesh_path.empty() ? std::string("assets/data/bunny.obj") : o.mesh_path;
  const bool fallback = !std::filesystem::exists(path);
  if (fallback && !o.mesh_path.empty()) throw std::invalid_argument("bench place: no such mesh '" + path + "'");
  // The object line: the bunny as default.jsonl loads it, or a sphere primitive in its place.
  json object_line = {{"name", "bunny"}, {"scale", 0.25}, {"translate", {1.5, 0.25, 0.0}}};
  if (fallback) {
    object_line["cmd"] = "scene.primitive";
    object_line["kind"] = "sphere";
  } else {
    object_line["cmd"] = "scene.load";
    object_line["path"] = std::filesystem::absolute(path).string();
  }

  json result = {{"bench", "place"},
                 {"cpu", bench_cpu_model()},
                 {"threads", tbb::info::default_concurrency()},
                 {"runs", o.runs},
                 {"samples", {o.samples_u, o.samples_v}}};
  std::vector<bool> spring_modes;
  if (o.springs != "off") spring_modes.push_back(true);
  if (o.springs != "on") spring_modes.push_back(false);

  json cases = json::array();
  for (const std::string& scene_name : o.scenes) {
    const PlaceScene ps = scene_lines(scene_name);
    core::Scene scene;
    History history(scene);
    for (const json& line : ps.setup) execute(history, line);
    execute(history, object_line);
    std::size_t scene_vertices = 0;
    for (const auto& obj : scene.objects())
      if (obj.name != "bunny" && obj.world_mesh) scene_vertices += obj.world_mesh->vertex_count();
    if (!result.contains("mesh")) {
      const auto* obj = scene.find("bunny");
      result["mesh"] = {{"source", fallback ? "scene.primitive sphere" : path},
                        {"fallback", fallback},
                        {"note", fallback ? "mesh file '" + path + "' not found; a sphere primitive is placed instead"
                                          : std::string()},
                        {"vertices", obj->world_mesh->vertex_count()}};
    }
    for (bool springs : spring_modes) {
      json line = ps.place;
      line["samples"] = {o.samples_u, o.samples_v};
      if (springs) line["springs"] = kSprings;
      err << "bench place: " << scene_name << (springs ? ", springs on" : ", springs off") << ", " << o.runs
          << " run(s)\n"
          << std::flush;
      const double warmup_ms = execute(history, line).milliseconds;
      history.undo();
      std::map<std::string, std::vector<double>> stage_ms;
      std::vector<double> totals;
      json last_stats;
      for (int r = 0; r < o.runs; ++r) {
        const ExecutionRecord rec = execute(history, line);
        double sum = 0.0;
        for (const ui::StageTiming& st : ui::stage_timings(rec.stats)) {
          stage_ms[st.name].push_back(st.ms);
          sum += st.ms;
        }
        stage_ms["other"].push_back(std::max(0.0, rec.milliseconds - sum));
        stage_ms["total"].push_back(rec.milliseconds);
        totals.push_back(rec.milliseconds);
        last_stats = rec.stats;
        history.undo();  // the bunny as it was: every run places the same rest mesh
      }
      json medians = json::object(), order = json::array();
      for (const ui::StageTiming& st : ui::stage_timings(last_stats)) {  // pipeline order (ui/frame_timings.h)
        medians[st.name] = bench_median(stage_ms.at(st.name));
        order.push_back(st.name);
      }
      for (const char* extra : {"other", "total"}) {
        medians[extra] = bench_median(stage_ms.at(extra));
        order.push_back(extra);
      }
      const json& sp = last_stats.contains("springs") ? last_stats.at("springs") : json::object();
      cases.push_back({{"scene", scene_name},
                       {"springs", springs},
                       {"scene_vertices", scene_vertices},
                       {"rays_total", last_stats.value("rays_total", 0)},
                       {"rays_hit", last_stats.value("rays_hit", 0)},
                       {"springs_steps", sp.value("steps", 0)},
                       {"springs_converged", sp.value("converged", false)},
                       {"warmup_ms", warmup_ms},
                       {"min_total_ms", *std::min_element(totals.begin(), totals.end())},
                       {"max_total_ms", *std::max_element(totals.begin(), totals.end())},
                       {"stages", order},
                       {"median_ms", medians}});
    }
  }
  result["cases"] = cases;
  return bench_emit(result, o.json, out, print_place_table);
}

}  // namespace trispline::editor
