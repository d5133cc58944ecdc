#include "bench/bench_dffd.h"

#include <tbb/info.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <thread>

#include "bench/bench_place.h"
#include "core/commands/incision_draw.h"
#include "core/dffd/dffd_cap.h"
#include "core/dffd/dffd_rig.h"
#include "core/incision/incision.h"
#include "core/mesh/loop_subdivision.h"
#include "core/mesh/mesh_io.h"
#include "core/raycast/ray_caster.h"
#include "editor/commands/command_log.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"

namespace trispline::editor {
namespace {
using json = nlohmann::json;

std::filesystem::path default_scene() { return "assets/scenes/seed/bars_walk.jsonl"; }  // run from the repository root

// incision.draw on the bunny Loop-subdivided once (139K vertices): a stroke across its flank (two surface points
// projected through a camera facing it), the command end to end through History, and incise() alone.
json bench_incision(int runs) {
  const core::TriMesh bunny = core::load_mesh("assets/data/bunny.obj");
  core::Scene scene;
  core::SceneObject o;
  o.name = "surface";
  o.source = "assets/data/bunny.obj (Loop ×1)";
  o.rest_mesh = std::make_shared<const core::TriMesh>(core::loop_subdivide(bunny, 1));
  o.refresh();
  scene.insert(o);
  core::Camera cam;
  cam.eye = {0.0, 0.2, 4.0};
  cam.target = {0.0, 0.0, 0.0};
  cam.viewport = {800, 600};
  scene.camera = cam;
  scene.camera_set = true;
  const glm::dvec3 a = cam.project({-0.45, 0.05, 0.6}), b = cam.project({0.35, -0.05, 0.6});
  json stroke = json::array();
  for (int i = 0; i < 16; ++i) {
    const double t = i / 15.0;
    stroke.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
  }
  const json line = {{"cmd", "incision.draw"}, {"object", "surface"}, {"stroke", stroke}, {"width", 0.06},
                     {"depth", 0.05},          {"opening", 0.02},     {"walls", true}};
  std::vector<double> command_ms, incise_ms;
  json stats;
  for (int r = 0; r < runs + 1; ++r) {
    core::Scene s = scene;
    History history(s);
    core::CommandContext ctx;
    auto cmd = CommandRegistry::builtin().parse(line, ctx);
    ExecutionRecord rec;
    const double ms = bench_ms([&] { rec = history.execute(std::move(cmd)); });
    if (!rec.ok) throw std::runtime_error("bench incision: " + rec.error);
    stats = rec.stats;
    if (r > 0) command_ms.push_back(ms);
  }
  const core::TriMesh& world = *scene.find("surface")->world_mesh;
  std::vector<glm::dvec2> px;
  for (const json& p : stroke) px.push_back({p[0].get<double>(), p[1].get<double>()});
  const core::RayCaster rays = core::stroke_ray_caster(world, cam, px, core::BuildQuality::high);
  const std::optional<core::IncisionFrame> frame = core::fit_incision_frame(px, cam, rays);
  core::IncisionParams params;
  params.width = 0.06;
  params.depth = 0.05;
  params.opening = 0.02;
  for (int r = 0; r < runs + 1 && frame; ++r) {
    const double ms = bench_ms([&] { (void)core::incise(world, *frame, params); });
    if (r > 0) incise_ms.push_back(ms);
  }
  return {{"surface_vertices", world.vertex_count()},
          {"stats", stats},
          {"command_ms", bench_median(command_ms)},
          {"incise_ms", incise_ms.empty() ? -1.0 : bench_median(incise_ms)}};
}

}  // namespace

int run_bench_dffd(const BenchDffdOptions& options, std::ostream& out, std::ostream& err) {
  const std::filesystem::path path =
      options.scene_path.empty() ? default_scene() : std::filesystem::path(options.scene_path);
  core::Scene scene;
  History history(scene);
  try {
    core::CommandContext ctx;
    ctx.base_dir = path.parent_path();
    for (const LogLine& line : read_log(path)) history.execute(CommandRegistry::builtin().parse(line.json, ctx));
  } catch (const std::exception& e) {
    err << "bench dffd: cannot replay " << path << ": " << e.what() << "\n";
    return 1;
  }
  const core::SceneObject* object = nullptr;
  for (const core::SceneObject& o : scene.objects())
    if (o.dffd && o.dffd_animated()) object = &o;
  if (!object) {
    err << "bench dffd: " << path << " has no animated dffd.split object\n";
    return 1;
  }
  const core::TriMesh rest = object->world_rest_mesh();
  const core::DffdRig& rig = *object->dffd;
  const core::Timeline& tl = scene.timeline;
  const int runs = std::max(1, options.runs), frames = std::max(1, options.frames);
  json rows = json::array();
  std::vector<double> all_total;
  for (int f = 0; f < frames; ++f) {
    const double frame =
        tl.frame_start + (frames == 1 ? 0.0 : double(f) * (tl.frame_end - tl.frame_start) / (frames - 1));
    const glm::dvec3 offset = object->offset_at(tl.time_of_frame(frame));
    // Split with caps and deform timed apart (dffd_split, dffd_deform on kept buffers); the warm per-frame path
    // (DffdFrameEvaluator: buffers kept, input vertices deformed while the split runs); and the cold dffd_apply
    // (fresh buffers every call: what SceneObject::refresh runs for every played or recorded frame).
    std::vector<double> split_ms, deform_ms, total_ms, cold_ms;
    core::DffdApplyStats st;
    std::size_t vertices = 0;
    core::DffdFrameEvaluator evaluator;
    core::MeshSplit split;
    core::TriMesh deformed;
    for (int r = 0; r < runs + 1; ++r) {  // one warm-up
      const double s = bench_ms([&] { core::dffd_split(rig, rest, offset, split, &st); });
      const double d = bench_ms([&] { core::dffd_deform(rig, split, deformed, &st); });
      const double t = bench_ms([&] { vertices = evaluator.evaluate(rig, rest, offset, &st).vertex_count(); });
      const double c = bench_ms([&] { (void)core::dffd_apply(rig, rest, offset); });
      if (r == 0) continue;
      split_ms.push_back(s);
      deform_ms.push_back(d);
      total_ms.push_back(t);
      cold_ms.push_back(c);
    }
    all_total.push_back(bench_median(total_ms));
    rows.push_back({{"frame", frame},
                    {"offset_u", offset.x},
                    {"cut_edges", st.cut_edges},
                    {"cap_triangles", st.cap_triangles},
                    {"outside_vertices", st.outside_vertices},
                    {"vertices", vertices},
                    {"split_cap_ms", bench_median(split_ms)},
                    {"deform_ms", bench_median(deform_ms)},
                    {"split_cap_deform_ms", bench_median(total_ms)},
                    {"cold_apply_ms", bench_median(cold_ms)}});
  }
  const json result = {
      {"scene", path.string()},
      {"object", object->name},
      {"rest_vertices", rest.vertex_count()},
      {"discontinuities", rig.discontinuities.size()},
      {"openings", core::dffd_openings_name(rig.openings)},
      {"lattice_controls",
       {rig.lattice.control_counts().x, rig.lattice.control_counts().y, rig.lattice.control_counts().z}},
      {"cpu", bench_cpu_model()},
      {"threads", tbb::info::default_concurrency()},
      {"runs", runs},
      {"frames", rows},
      {"max_frame_ms", *std::max_element(all_total.begin(), all_total.end())},
      {"median_frame_ms", bench_median(all_total)},
      {"incision", bench_incision(runs)}};
  if (options.json) {
    out << result.dump(2) << "\n";
    return 0;
  }
  out << "DFFD walk: " << result["object"].get<std::string>() << " (" << rest.vertex_count() << " vertices), "
      << rig.discontinuities.size() << " discontinuities, openings " << result["openings"].get<std::string>() << ", "
      << result["threads"] << " threads, " << result["cpu"].get<std::string>() << "\n";
  out << "   frame  offset_u  cut_edges  cap_tris  vertices  split+cap ms  deform ms  frame ms  cold dffd_apply ms\n";
  for (const json& r : rows)
    out << std::setw(8) << bench_fixed(r["frame"].get<double>(), 1) << std::setw(10)
        << bench_fixed(r["offset_u"].get<double>(), 3) << std::setw(11) << r["cut_edges"].get<std::size_t>()
        << std::setw(10) << r["cap_triangles"].get<std::size_t>() << std::setw(10) << r["vertices"].get<std::size_t>()
        << std::setw(14) << bench_fixed(r["split_cap_ms"].get<double>(), 2) << std::setw(11)
        << bench_fixed(r["deform_ms"].get<double>(), 2) << std::setw(10)
        << bench_fixed(r["split_cap_deform_ms"].get<double>(), 2) << std::setw(20)
        << bench_fixed(r["cold_apply_ms"].get<double>(), 2) << "\n";
  out << "median frame " << bench_fixed(result["median_frame_ms"].get<double>(), 2) << " ms, max frame "
      << bench_fixed(result["max_frame_ms"].get<double>(), 2) << " ms (split + cap + deform, warm buffers; median of "
      << runs << " runs each)\n";
  const json& inc = result["incision"];
  out << "incision.draw on " << inc["surface_vertices"] << " vertices (bunny, Loop x1): command "
      << bench_fixed(inc["command_ms"].get<double>(), 2) << " ms, incise() "
      << bench_fixed(inc["incise_ms"].get<double>(), 2) << " ms (median of " << runs << "); "
      << inc["stats"].value("cut_edges", 0) << " cut edges, " << inc["stats"].value("wall_faces", 0) << " wall faces\n";
  return 0;
}

}  // namespace trispline::editor
