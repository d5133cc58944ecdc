// `trispline bench ddm`: see bench_ddm.h.
#include "bench/bench_ddm.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"
#include "bench/bench_place.h"
#include "editor/history.h"
#include "editor/render_scene.h"
#include "editor/replay.h"
#include "gpu/gl_context.h"
#include "gpu/renderer.h"

namespace trispline::editor {
namespace {
using json = nlohmann::json;

const std::vector<std::string> kCases = {"thorns_face", "thorns_teapot", "chains_1m", "chains_3m"};
// The face case replays the shipped scene (seed Table 5.1's first row); it needs the repository's assets.
const std::filesystem::path kFaceScene = "assets/scenes/face_thorns.jsonl";
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

std::string cell(const json& v, int digits) { return v.is_number() ? bench_fixed(v.get<double>(), digits) : "-"; }

void print_table(const json& j, std::ostream& out) {
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
}

}  // namespace

int run_bench_ddm(const BenchDdmOptions& options, std::ostream& out, std::ostream& err) {
  std::vector<std::string> names = options.cases.empty() ? kCases : options.cases;
  for (const std::string& n : names)
    if (std::find(kCases.begin(), kCases.end(), n) == kCases.end()) {
      err << "bench ddm: unknown case '" << n << "' (thorns_face, thorns_teapot, chains_1m, chains_3m)\n";
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
  return bench_emit(result, options.json, out, print_table);
}

}  // namespace trispline::editor
