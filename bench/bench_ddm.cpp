// `trispline bench ddm`: see bench_ddm.h.
#include "bench/bench_ddm.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "bench/bench_place.h"
#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/scene/ddm_follow.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "editor/replay/render_scene.h"
#include "editor/replay/replay.h"
#include "editor/tools/ddm_paint_tool.h"
#include "gpu/gl/gl_context.h"
#include "gpu/render/renderer.h"

namespace trispline::editor {
namespace {
using json = nlohmann::json;

const std::vector<std::string> kCases = {"thorns_face", "thorns_teapot", "chains_1m", "chains_3m"};
const std::vector<std::string> kOrbitCases = {"orbit_default", "orbit_fine"};
const std::vector<std::string> kFollowCases = {"follow_bunny"};
const std::filesystem::path kFollowScene = "assets/scenes/seed/thorny_walk.jsonl";
constexpr double kFollowTileSize = 0.058;  // object units: about 1 M tile vertices on the bunny
const std::filesystem::path kDefaultScene = "assets/scenes/default.jsonl";
// The face case replays the shipped scene (seed Table 5.1's first row); it needs the repository's assets.
const std::filesystem::path kFaceScene = "assets/scenes/seed/face_thorns.jsonl";
const std::filesystem::path kFaceMesh = "assets/data/nefertiti.off";

struct Case {
  std::string name, base, tile;
  core::Scene scene;
  std::shared_ptr<const core::DdmLayer> layer;
  core::Camera camera;
  double setup_ms = 0.0;
};

core::SceneObject mesh_object(const std::string& name, const std::string& source, core::TriMesh mesh) {
  core::SceneObject o;
  o.name = name;
  o.source = source;
  o.color = {0.55f, 0.42f, 0.30f};
  o.rest_mesh = std::make_shared<const core::TriMesh>(std::move(mesh));
  o.refresh();
  return o;
}

// The layer over all of `charts` of `base` with one `tile` per cell of an n × m rect layout.
std::shared_ptr<core::DdmLayer> layer_over(const core::DdmBase& base, const std::string& tile, glm::ivec2 counts,
                                           glm::ivec2 map_resolution, double height) {
  auto layer = std::make_shared<core::DdmLayer>();
  layer->name = tile + "s";
  layer->tile_sources = {tile};
  layer->tiles = {core::make_ddm_tile(tile)};
  layer->counts = counts;
  layer->height = height;
  layer->instances = core::ddm_layout_cells(core::DdmLayout::rect, counts, base.chart_count());
  std::vector<int> charts(static_cast<std::size_t>(base.chart_count()));
  for (int c = 0; c < base.chart_count(); ++c) charts[static_cast<std::size_t>(c)] = c;
  layer->maps = std::make_shared<const core::DdmMaps>(core::ddm_sample_maps(base, charts, map_resolution));
  return layer;
}

Case make_case(const std::string& name, const BenchDdmOptions& o) {
  Case c;
  c.name = name;
  core::SceneObject object;
  c.setup_ms = bench_ms([&] {
    if (name == "thorns_face") {
      c.base = "Loop limit surface of the Nefertiti face mask (562 triangles), one painted stroke";
      c.tile = "thorn";
      History history(c.scene);
      const ReplayResult r = replay_lines(history, kFaceScene);
      if (!r.ok) throw std::runtime_error("bench ddm: thorns_face: " + r.error);
      for (const core::SceneObject& obj : c.scene.objects())
        if (!obj.ddm_layers.empty()) c.layer = obj.ddm_layers.front();
      if (!c.layer) throw std::runtime_error("bench ddm: thorns_face: the scene has no tile layer");
    } else if (name == "thorns_teapot") {
      c.base = "teapot body (8 Bézier patches, one periodic chart)";
      c.tile = "thorn";
      object = mesh_object("teapot", "primitive:teapot", core::make_primitive(core::PrimitiveKind::Teapot));
      auto base = std::make_shared<const core::DdmSplineBase>(core::teapot_body_patches(), glm::ivec2(4, 2),
                                                              glm::bvec2(true, false));
      auto layer = layer_over(*base, "thorn", {32, 20}, {129, 65}, 0.045);
      layer->base = core::DdmBaseKind::teapot_body;
      layer->surface = base;
      layer->offset_velocity = {0.02, 0.0};  // the thorns crawl round the pot (seed §5.4.2)
      c.layer = layer;
    } else {
      const bool big = name == "chains_3m";
      const core::TriMesh sphere = core::make_sphere(big ? 34 : 18, big ? 14 : 9);
      c.base = "Loop limit surface of a sphere (" + std::to_string(sphere.triangle_count()) + " triangles, " +
               std::to_string(3 * sphere.triangle_count()) + " charts)";
      c.tile = "chain";
      object = mesh_object("ball", "primitive:sphere", sphere);
      auto base = std::make_shared<const core::DdmSubdivBase>(sphere);
      auto layer = layer_over(*base, "chain", {1, 1}, {9, 9}, big ? 0.06 : 0.1);
      layer->base = core::DdmBaseKind::limit;
      layer->surface = base;
      c.layer = layer;
    }
  });
  if (name == "thorns_face") {
    c.camera = render_camera(c.scene, o.width, o.height);
    return c;
  }
  object.ddm_layers.push_back(c.layer);
  c.scene.insert(object);
  const core::Aabb b = c.scene.bounds();
  const glm::dvec3 centre = b.center();
  const double size = std::max(b.diagonal(), 1e-6);
  c.camera.target = centre;
  c.camera.eye = centre + size * glm::dvec3(0.55, 0.45, 0.95);
  c.camera.fov_deg = 45.0;
  c.camera.viewport = {o.width, o.height};
  return c;
}

json stats_of(const std::vector<double>& v) {
  if (v.empty()) return {{"median", nullptr}, {"min", nullptr}, {"max", nullptr}};
  return {{"median", bench_median(v)},
          {"min", *std::min_element(v.begin(), v.end())},
          {"max", *std::max_element(v.begin(), v.end())}};
}

json run_case(Case& c, const BenchDdmOptions& o, gpu::Renderer& renderer, gpu::OffscreenTarget& target,
              std::ostream& err) {
  const core::DdmLayer& layer = *c.layer;
  const std::size_t tile_vertices = layer.tiles[0].mesh.vertex_count();
  const std::size_t vertices = tile_vertices * layer.instances.size();
  err << "bench ddm: " << c.name << ": " << vertices << " tile vertices\n" << std::flush;
  json cpu_ms = nullptr;
  if (o.cpu_reference) cpu_ms = bench_ms([&] { (void)core::ddm_layer_mesh(layer, 0.0); });
  gpu::ViewOptions view;
  target.bind();
  const auto frame = [&](double t) {
    view.time_s = t;
    return bench_ms([&] {
      renderer.draw(c.scene, c.camera, view);
      glFinish();
    });
  };
  const double first_ms = frame(0.0);  // uploads, shader compilation (llvmpipe JIT-compiles at first draw)
  for (int w = 0; w < 2; ++w) frame(0.0);
  std::vector<double> frame_ms, ddm_ms, draw_ms;
  for (int f = 0; f < o.frames; ++f) {
    frame_ms.push_back(frame((f + 1) / 24.0));
    const gpu::RenderStats& s = renderer.last_stats();
    if (s.ddm_vertices != vertices)
      throw std::runtime_error("bench ddm: the renderer drew " + std::to_string(s.ddm_vertices) +
                               " tile vertices, not " + std::to_string(vertices));
    if (s.ddm_ms >= 0.0) ddm_ms.push_back(s.ddm_ms);  // query mode: the newest finished frame's
    if (s.draw_ms >= 0.0) draw_ms.push_back(s.draw_ms);
  }
  const double frame_median = bench_median(frame_ms);
  const json ddm = stats_of(ddm_ms);
  json r = {{"name", c.name},
            {"base", c.base},
            {"tile", c.tile},
            {"instances", layer.instances.size()},
            {"tile_vertices", tile_vertices},
            {"vertices", vertices},
            {"setup_ms", c.setup_ms},
            {"first_frame_ms", first_ms},
            {"cpu_reference_ms", cpu_ms},
            {"ddm_gpu_ms", ddm},
            {"draw_ms_median", draw_ms.empty() ? json(nullptr) : json(bench_median(draw_ms))},
            {"frame_ms", stats_of(frame_ms)},
            {"fps", 1000.0 / frame_median}};
  r["vertices_per_s"] = ddm_ms.empty() || bench_median(ddm_ms) <= 0.0
                            ? json(nullptr)
                            : json(double(vertices) / (bench_median(ddm_ms) / 1000.0));
  return r;
}

// The default scene with its teapot filled by the Tile Paint panel's defaults (tile size × `tile_scale`).
json run_orbit(const std::string& name, const BenchDdmOptions& o, gpu::Renderer& renderer, gpu::OffscreenTarget& target,
               std::ostream& err) {
  core::Scene scene;
  History history(scene);
  const ReplayResult r = replay_lines(history, kDefaultScene);
  if (!r.ok) throw std::runtime_error("bench ddm: " + name + ": " + r.error);
  const core::SceneObject* pot = scene.find("teapot");
  if (!pot) throw std::runtime_error("bench ddm: " + name + ": default.jsonl has no teapot");
  DdmPaintToolParams params;
  params.paint.spec.base = core::ddm_default_base(*pot);
  params.paint.spec.tile_size = ddm_default_tile_size(pot) * (name == "orbit_fine" ? 0.25 : 1.0);
  const nlohmann::json line = ddm_fill_line("teapot", params);
  const core::CommandContext ctx{std::filesystem::current_path(), {}};
  const double fill_ms = bench_ms([&] { history.execute(CommandRegistry::builtin().parse(line, ctx)); });
  const core::DdmLayer& layer = *scene.find("teapot")->ddm_layers.front();
  const std::size_t vertices = layer.mesh->vertex_count();
  err << "bench ddm: " << name << ": " << layer.instances.size() << " tiles, " << vertices << " tile vertices\n"
      << std::flush;
  const core::Camera home = scene.camera_set ? scene.camera : render_camera(scene, o.width, o.height);
  core::Camera cam = home;
  cam.viewport = {o.width, o.height};
  const auto orbit = [&](int f) {  // 3° per frame round the target's vertical axis
    const double a = glm::radians(3.0 * f);
    const glm::dvec3 d = home.eye - home.target;
    cam.eye =
        home.target + glm::dvec3(std::cos(a) * d.x + std::sin(a) * d.z, d.y, -std::sin(a) * d.x + std::cos(a) * d.z);
  };
  const bool software = gpu::is_software_renderer();
  json modes = json::array();
  for (const std::string mode : {"rest", "orbit_all", "orbit_cull", "orbit_lod"}) {
    gpu::ViewOptions view;
    view.ddm.cull = mode == "orbit_cull" || mode == "orbit_lod";
    view.ddm.moving = mode == "orbit_lod";
    view.ddm.motion_budget_vertices = software ? gpu::kDdmMotionBudgetVerticesSoftware : gpu::kDdmMotionBudgetVertices;
    target.bind();
    std::vector<double> frame_ms, drawn, culled, keep;
    for (int f = -2; f < o.frames; ++f) {
      orbit(mode == "rest" ? 0 : f);
      const double ms = bench_ms([&] {
        renderer.draw(scene, cam, view);
        glFinish();
      });
      if (f < 0) continue;  // warm-up
      const gpu::RenderStats& s = renderer.last_stats();
      frame_ms.push_back(ms);
      drawn.push_back(double(s.ddm_instances_drawn));
      culled.push_back(double(s.ddm_instances_culled));
      keep.push_back(s.ddm_keep);
    }
    modes.push_back({{"mode", mode},
                     {"frame_ms", stats_of(frame_ms)},
                     {"fps", 1000.0 / bench_median(frame_ms)},
                     {"drawn_median", bench_median(drawn)},
                     {"culled_median", bench_median(culled)},
                     {"keep_median", bench_median(keep)}});
  }
  renderer.release_unused(core::Scene{});
  return {{"name", name},
          {"tile_size", *params.paint.spec.tile_size},
          {"base", core::ddm_base_name(*params.paint.spec.base)},
          {"instances", layer.instances.size()},
          {"vertices", vertices},
          {"fill_ms", fill_ms},
          {"modes", modes}};
}

std::string cell(const json& v, int digits) { return v.is_number() ? bench_fixed(v.get<double>(), digits) : "-"; }

void print_ddm_table(const json& j, std::ostream& out) {
  out << "bench ddm: live DDM layers, one instanced draw per tile mesh (seed §5.3.2)\n"
      << "renderer: " << j["renderer"].get<std::string>() << "  " << j["width"] << "x" << j["height"] << " x"
      << j["samples"] << " MSAA, " << j["frames"] << " frames per case\n"
      << "timer: " << j["timer_mode"].get<std::string>() << "\n"
      << "cpu: " << j["cpu"].get<std::string>() << " (" << j["threads"] << " threads)\n\n";
  out << std::left << std::setw(15) << "case" << std::right << std::setw(11) << "vertices" << std::setw(11)
      << "instances" << std::setw(13) << "ddm GPU ms" << std::setw(11) << "frame ms" << std::setw(9) << "fps"
      << std::setw(11) << "Mvert/s" << std::setw(13) << "CPU ref ms"
      << "\n";
  for (const json& c : j["cases"]) {
    const json& vps = c["vertices_per_s"];
    out << std::left << std::setw(15) << c["name"].get<std::string>() << std::right << std::setw(11)
        << c["vertices"].get<std::size_t>() << std::setw(11) << c["instances"].get<std::size_t>() << std::setw(13)
        << cell(c["ddm_gpu_ms"]["median"], 2) << std::setw(11) << cell(c["frame_ms"]["median"], 2) << std::setw(9)
        << cell(c["fps"], 1) << std::setw(11) << (vps.is_number() ? bench_fixed(vps.get<double>() / 1e6, 1) : "-")
        << std::setw(13) << cell(c["cpu_reference_ms"], 1) << "\n";
  }
  out << "\n(ddm GPU ms: the layer pass, RenderStats::ddm_ms; frame ms: draw() + glFinish, wall clock; medians)\n";
  if (j.contains("follow")) {
    const json& f = j["follow"];
    out << "\nfollow_bunny: " << f["instances"] << " thorns, " << f["vertices"]
        << " tile vertices carried by the placement's FFD, per frame (median ms)\n"
        << "  cpu_ref (double, DDM cached):      " << cell(f["cpu_reference_ms"]["median"], 1) << "\n"
        << "  cpu_fast (float, positions+normals): " << cell(f["cpu_fast_frame_ms"]["median"], 1) << "  (bind "
        << cell(f["cpu_fast_bind_ms"], 0) << " ms once; max error " << f["cpu_fast_max_error_rel"].get<double>()
        << " × size)\n"
        << "  DDM stage (an animated layer adds): " << cell(f["ddm_stage_ms"]["median"], 1) << "\n"
        << "  GLSL FOLLOW+FFD: frame " << cell(f["glsl_frame_ms"]["median"], 1) << ", layer pass "
        << cell(f["glsl_layer_ms"]["median"], 1) << "\n";
  }
  if (!j.contains("orbit") || j["orbit"].empty()) return;
  out << "\norbit: default.jsonl, the teapot filled by the Tile Paint panel's defaults, 3 deg per frame, "
      << j["orbit_samples"] << " sample(s)\n";
  out << std::left << std::setw(15) << "case" << std::setw(12) << "mode" << std::right << std::setw(11) << "frame ms"
      << std::setw(9) << "fps" << std::setw(10) << "drawn" << std::setw(10) << "culled" << std::setw(8) << "share"
      << "\n";
  for (const json& c : j["orbit"]) {
    out << c["name"].get<std::string>() << ": tile size " << c["tile_size"] << ", " << c["instances"] << " tiles, "
        << c["vertices"] << " tile vertices, fill " << bench_fixed(c["fill_ms"].get<double>(), 0) << " ms\n";
    for (const json& m : c["modes"])
      out << std::left << std::setw(15) << "" << std::setw(12) << m["mode"].get<std::string>() << std::right
          << std::setw(11) << cell(m["frame_ms"]["median"], 1) << std::setw(9) << cell(m["fps"], 1) << std::setw(10)
          << cell(m["drawn_median"], 0) << std::setw(10) << cell(m["culled_median"], 0) << std::setw(8)
          << cell(m["keep_median"], 3) << "\n";
  }
}

// The thorny bunny walking over the teapot (assets/scenes/seed/thorny_walk.jsonl without its recording, thorns at
// kFollowTileSize): the tile layer carried by the placement's FFD every frame, three ways.
json run_follow(const BenchDdmOptions& o, gpu::Renderer& renderer, gpu::OffscreenTarget& target, std::ostream& err) {
  // The log with absolute data paths (it is written elsewhere) and the finer tiles.
  std::ifstream in(kFollowScene);
  const std::filesystem::path tmp = std::filesystem::temp_directory_path() / "trispline_bench_follow.jsonl";
  {
    std::ofstream log(tmp);
    const std::string data =
        std::filesystem::weakly_canonical(std::filesystem::absolute(kFollowScene).parent_path() / "../../data")
            .string() +
        "/";
    for (std::string line; std::getline(in, line);) {
      if (line.find("\"anim.record\"") != std::string::npos) continue;
      const std::string relative_data = "../../data/";  // the scene's data paths, relative to assets/scenes/seed/
      if (const std::size_t at = line.find(relative_data); at != std::string::npos)
        line.replace(at, relative_data.size(), data);
      const std::string size_field = "\"tile_size\":0.1";
      if (const std::size_t at = line.find(size_field); at != std::string::npos)
        line.replace(at, size_field.size(), "\"tile_size\":" + std::to_string(kFollowTileSize));
      log << line << "\n";
    }
  }
  core::Scene scene;
  History history(scene);
  const ReplayResult r = replay_lines(history, tmp);
  std::filesystem::remove(tmp);
  if (!r.ok) throw std::runtime_error("bench ddm: follow_bunny: " + r.error);
  const core::SceneObject& bunny = *scene.find("bunny");
  const core::DdmLayer& layer = *bunny.ddm_layers.front();
  const std::size_t vertices = layer.mesh->vertex_count();
  err << "bench ddm: follow_bunny: " << layer.instances.size() << " tiles, " << vertices << " tile vertices\n"
      << std::flush;
  const auto time_of = [&](int f) { return scene.timeline.time_of_frame(scene.timeline.frame_start + f % 24); };
  // CPU reference (double) and the DDM stage alone (what an animated layer adds), 3 frames each.
  std::vector<double> reference_ms, ddm_ms;
  core::TriMesh reference;
  for (int f = 0; f < 3; ++f) {
    reference_ms.push_back(
        bench_ms([&] { reference = core::ddm_layer_world_mesh(bunny, layer, *layer.mesh, time_of(f)); }));
    ddm_ms.push_back(bench_ms([&] { (void)core::ddm_layer_mesh(layer, time_of(f)); }));
  }
  // cpu_fast: bound once, evaluated per frame with normals.
  core::DdmFastFollower fast;
  const double bind_ms = bench_ms([&] { fast.bind(bunny, *layer.mesh); });
  std::vector<glm::vec3> p, n;
  std::vector<double> fast_ms;
  for (int f = -2; f < o.frames; ++f) {
    const double ms = bench_ms([&] { fast.evaluate(bunny.offset_at(time_of(std::max(f, 0))), p, n); });
    if (f >= 0) fast_ms.push_back(ms);
  }
  fast.evaluate(bunny.offset_at(time_of(2)), p, n);  // the reference's last frame
  core::Aabb box;
  for (const glm::dvec3& q : reference.positions) box.extend(q);
  double worst = 0.0;
  for (std::size_t v = 0; v < p.size(); ++v)
    worst = std::max(worst, glm::length(glm::dvec3(p[v]) - reference.positions[v]));
  // GLSL: the renderer's FOLLOW + FFD variant (the whole frame, and the layer pass alone).
  core::Camera cam = scene.camera;
  cam.viewport = {o.width, o.height};
  target.bind();
  std::vector<double> frame_ms, layer_ms;
  for (int f = -2; f < o.frames; ++f) {
    gpu::ViewOptions view;
    view.time_s = time_of(std::max(f, 0));
    const double ms = bench_ms([&] {
      renderer.draw(scene, cam, view);
      glFinish();
    });
    if (f < 0) continue;
    frame_ms.push_back(ms);
    layer_ms.push_back(renderer.last_stats().ddm_ms);
  }
  return {{"name", "follow_bunny"},
          {"tile_size", kFollowTileSize},
          {"instances", layer.instances.size()},
          {"vertices", vertices},
          {"cpu_reference_ms", stats_of(reference_ms)},
          {"ddm_stage_ms", stats_of(ddm_ms)},
          {"cpu_fast_bind_ms", bind_ms},
          {"cpu_fast_frame_ms", stats_of(fast_ms)},
          {"cpu_fast_max_error_rel", worst / box.diagonal()},
          {"glsl_frame_ms", stats_of(frame_ms)},
          {"glsl_layer_ms", stats_of(layer_ms)}};
}

}  // namespace

int run_bench_ddm(const BenchDdmOptions& options, std::ostream& out, std::ostream& err) {
  std::vector<std::string> names = options.cases.empty() ? kCases : options.cases;
  if (options.cases.empty()) names.insert(names.end(), kOrbitCases.begin(), kOrbitCases.end());
  if (options.cases.empty()) names.insert(names.end(), kFollowCases.begin(), kFollowCases.end());
  std::vector<std::string> orbits;
  bool follow = false;
  for (const std::string& n : names)
    if (std::find(kOrbitCases.begin(), kOrbitCases.end(), n) != kOrbitCases.end())
      orbits.push_back(n);
    else if (n == "follow_bunny")
      follow = true;
    else if (std::find(kCases.begin(), kCases.end(), n) == kCases.end()) {
      err << "bench ddm: unknown case '" << n
          << "' (thorns_face, thorns_teapot, chains_1m, chains_3m, orbit_default, orbit_fine, follow_bunny)\n";
      return 1;
    }
  std::erase_if(names, [&](const std::string& n) {
    return n == "follow_bunny" || std::find(orbits.begin(), orbits.end(), n) != orbits.end();
  });
  if (follow && !std::filesystem::exists(kFollowScene)) {
    if (!options.cases.empty()) {
      err << "bench ddm: follow_bunny needs " << kFollowScene.string() << " (run the bench from the repository root)\n";
      return 1;
    }
    err << "bench ddm: skipping follow_bunny: it needs " << kFollowScene.string() << "\n";
    follow = false;
  }
  if (!orbits.empty() && !std::filesystem::exists(kDefaultScene)) {
    err << "bench ddm: the orbit cases need " << kDefaultScene.string()
        << " (run the bench from the repository root)\n";
    return 1;
  }
  const bool have_face = std::filesystem::exists(kFaceScene) && std::filesystem::exists(kFaceMesh);
  if (!have_face) {
    const std::string why = "needs " + kFaceScene.string() + " and " + kFaceMesh.string() +
                            " (run scripts/fetch_assets.sh, then the bench from the repository root)";
    if (!options.cases.empty() && std::find(names.begin(), names.end(), "thorns_face") != names.end()) {
      err << "bench ddm: case thorns_face " << why << "\n";
      return 1;
    }
    err << "bench ddm: skipping thorns_face: it " << why << "\n";
    names.erase(std::remove(names.begin(), names.end(), "thorns_face"), names.end());
  }
  // Declared first: the renderer's GL objects are deleted while the context is still current.
  std::unique_ptr<gpu::HeadlessContext> context;
  try {
    context = std::make_unique<gpu::HeadlessContext>();
  } catch (const gpu::GlContextError& e) {
    err << "bench ddm: no GL context: " << e.what() << "\n";
    return 1;
  }
  gpu::Renderer renderer;
  gpu::OffscreenTarget target(options.width, options.height, options.samples);
  json result = {{"bench", "ddm"},
                 {"renderer", context->renderer()},
                 {"timer_mode", renderer.last_stats().timer_mode},
                 {"cpu", bench_cpu_model()},
                 {"threads", std::thread::hardware_concurrency()},
                 {"width", options.width},
                 {"height", options.height},
                 {"samples", target.samples()},
                 {"frames", options.frames},
                 {"cases", json::array()}};
  for (const std::string& n : names) {
    try {
      Case c = make_case(n, options);
      result["cases"].push_back(run_case(c, options, renderer, target, err));
    } catch (const std::exception& e) {
      err << e.what() << "\n";
      return 1;
    }
    result["timer_mode"] = renderer.last_stats().timer_mode;
    renderer.release_unused(core::Scene{});  // free this case's buffers before the next
  }
  if (!orbits.empty()) {
    // As the editor's window: no MSAA on a software renderer (editor/app.cpp's make_window).
    const int samples = gpu::is_software_renderer() ? 1 : options.samples;
    gpu::OffscreenTarget orbit_target(options.width, options.height, samples);
    result["orbit_samples"] = orbit_target.samples();
    result["orbit"] = json::array();
    for (const std::string& n : orbits) {
      try {
        result["orbit"].push_back(run_orbit(n, options, renderer, orbit_target, err));
      } catch (const std::exception& e) {
        err << e.what() << "\n";
        return 1;
      }
    }
  }
  if (follow) {
    try {
      result["follow"] = run_follow(options, renderer, target, err);
    } catch (const std::exception& e) {
      err << e.what() << "\n";
      return 1;
    }
  }
  return bench_emit(result, options.json, out, print_ddm_table);
}

}  // namespace trispline::editor
