// `trispline bench press`: a pressing drag on a ~1 M-vertex object, per drag sample. See bench_place.h.
#include <epoxy/gl.h>
#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/bench_place.h"
#include "core/ffd/ffd_evaluator.h"
#include "core/mesh/bilinear_subdivision.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/uv_sphere.h"
#include "core/raycast/ray_caster.h"
#include "editor/commands/command_registry.h"
#include "editor/session/session.h"
#include "editor/tools/press_tool.h"
#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/gl_context.h"
#include "gpu/gl/mesh_buffers.h"
#include "ui/message_log.h"

namespace trispline::editor {

namespace {

using nlohmann::json;
constexpr double kInteractive = 30.0;  // updates per second
constexpr double kStrength = 0.05;     // world units, the Press tool's default

// The big mesh: `path` (or a UV sphere of ~target vertices when the default file is absent) refined with OpenSubdiv
// bilinear subdivision to the level whose vertex count is closest to `target`.
core::TriMesh big_mesh(const BenchPressOptions& o, json& info) {
  const std::string path = o.mesh_path.empty() ? std::string("assets/data/bunny.obj") : o.mesh_path;
  if (!std::filesystem::exists(path)) {
    if (!o.mesh_path.empty()) throw std::invalid_argument("bench press: no such mesh '" + path + "'");
    const int rings = std::max(2, int(std::lround(std::sqrt(double(o.vertices) / 2.0))));
    const int segments = std::max(3, int(std::lround(double(o.vertices) / rings)));
    core::TriMesh m = core::make_uv_sphere(1.0, rings, segments);
    info = {{"source", "generated sphere (" + std::to_string(rings) + " x " + std::to_string(segments) + ")"},
            {"fallback", true},
            {"note", "mesh file '" + path + "' not found; using a generated sphere"},
            {"base_vertices", m.vertex_count()},
            {"subdivision_level", 0}};
    return m;
  }
  const core::TriMesh base = core::load_mesh(path);
  // Vertex counts per level (bilinear: one new vertex per edge and per face; triangles become 3 quads, quads 4).
  double v = double(base.vertex_count()), f = double(base.triangle_count()), e = 1.5 * f;
  int level = 0;
  double best = std::abs(std::log(v / double(o.vertices)));
  for (int l = 1; l <= 4; ++l) {
    const double quads = l == 1 ? 3 * f : 4 * f, edges = l == 1 ? 2 * e + 3 * f : 2 * e + 4 * f;
    v += e + f;
    e = edges;
    f = quads;
    if (std::abs(std::log(v / double(o.vertices))) < best) best = std::abs(std::log(v / double(o.vertices))), level = l;
  }
  info = {{"source", path},
          {"fallback", false},
          {"note", ""},
          {"base_vertices", base.vertex_count()},
          {"subdivision_level", level}};
  return core::subdivide_bilinear(base, level);
}

json stage(const std::string& name, double ms) {
  const double rate = ms > 0 ? 1000.0 / ms : 0.0;
  return {{"stage", name}, {"median_ms", ms}, {"updates_per_s", rate}, {"interactive", rate >= kInteractive}};
}

void print_press_table(const json& r, std::ostream& os) {
  const json& m = r.at("mesh");
  const json& d = r.at("drag");
  const json& t = r.at("tool");
  os << "Pressing drag on " << r.at("cpu").get<std::string>() << " (" << r.at("threads")
     << " threads), GL: " << r.at("renderer").get<std::string>() << "\n"
     << "object: " << m.at("source").get<std::string>() << ", " << m.at("base_vertices") << " -> " << m.at("vertices")
     << " vertices (bilinear level " << m.at("subdivision_level") << "), placed on the teapot in "
     << bench_fixed(r.at("place_ms").get<double>(), 0) << " ms; lattice " << r.at("lattice").at("controls").dump()
     << ", order " << r.at("lattice").at("order").dump() << "\n"
     << "drag: " << d.at("pixels") << " mouse moves, " << d.at("samples") << " path samples, radius "
     << bench_fixed(d.at("radius").get<double>(), 4) << ", strength " << d.at("strength") << "; median of "
     << r.at("runs") << "\n\n";
  if (m.at("fallback").get<bool>()) os << "NOTE: " << m.at("note").get<std::string>() << "\n\n";
  os << "Press tool as it is (editor/tools/press_tool.cpp): per mouse move "
     << bench_fixed(t.at("move_median_ms").get<double>(), 3) << " ms median, "
     << bench_fixed(t.at("move_max_ms").get<double>(), 2)
     << " ms max (ray cast + path; the live preview is drawn once per frame: rows (a)+(b) below)\n"
     << "  first hover on the object (BVH build over world_mesh): "
     << bench_fixed(t.at("first_hover_ms").get<double>(), 1) << " ms; "
     << "first hover after a release (BVH rebuilt): " << bench_fixed(t.at("hover_after_release_ms").get<double>(), 1)
     << " ms\n  parts: BVH build " << bench_fixed(t.at("bvh_build_ms").get<double>(), 1) << " ms, one ray cast "
     << bench_fixed(t.at("ray_cast_ms").get<double>(), 3) << " ms, default radius (bounding box of world_mesh) "
     << bench_fixed(t.at("default_radius_ms").get<double>(), 3) << " ms\n\n";
  os << std::left << std::setw(68) << "per update" << std::right << std::setw(11) << "ms" << std::setw(11)
     << "updates/s" << std::setw(14) << "interactive\n";
  for (const json& s : r.at("per_update"))
    os << std::left << std::setw(68) << s.at("stage").get<std::string>() << std::right << std::setw(11)
       << bench_fixed(s.at("median_ms").get<double>(), 2) << std::setw(11)
       << bench_fixed(s.at("updates_per_s").get<double>(), 1) << std::setw(13)
       << (s.at("interactive").get<bool>() ? "yes" : "NO") << "\n";
  os << "\nbind (once per drag / binding): cpu_fast " << bench_fixed(r.at("bind_ms").value("cpu_fast", 0.0), 2)
     << " ms, glsl_compute " << bench_fixed(r.at("bind_ms").value("glsl_compute", 0.0), 2) << " ms\n"
     << "interactive = at least " << kInteractive << " updates per second.\n";
}

// A GL context when `gpu` and one can be made; `renderer` names it or says why there is none.
std::unique_ptr<gpu::HeadlessContext> open_context(bool gpu, std::string& renderer, std::ostream& err) {
  std::unique_ptr<gpu::HeadlessContext> context;
  renderer = "none (--cpu-only)";
  if (gpu) {
    try {
      context = std::make_unique<gpu::HeadlessContext>();
      renderer = context->renderer();
    } catch (const gpu::GlContextError& e) {
      renderer = std::string("none (no GL context: ") + e.what() + ")";
      err << "bench press: no GL context, GLSL skipped: " << e.what() << "\n";
    }
  }
  return context;
}

// The teapot scene with the big object "bunny" placed on it (the scene set-up and placement are commands).
// Returns place.sketch's milliseconds.
double place_big_object(EditorSession& session, const ui::MessageLog& messages, core::TriMesh mesh,
                        const json& mesh_info, const std::function<void(const std::string&)>& progress) {
  auto execute = [&](const json& line) {
    if (!session.execute(line))
      throw std::runtime_error("bench press: " + line.value("cmd", std::string("?")) +
                               " failed: " + (messages.messages().empty() ? "" : messages.messages().back().text));
  };
  std::vector<json> lines = bench_place_scene("teapot");
  json place = lines.back();
  lines.pop_back();
  for (const json& l : lines) execute(l);
  {
    core::SceneObject obj;  // inserted directly: the subdivided mesh has no file for scene.load
    obj.name = "bunny";
    obj.source = mesh_info.at("source").get<std::string>() + " (subdivided)";
    obj.rest_mesh = std::make_shared<const core::TriMesh>(std::move(mesh));
    obj.transform.scale = glm::dvec3(0.25);
    obj.transform.translate = {1.5, 0.25, 0.0};
    obj.refresh();
    session.scene().insert(std::move(obj));
  }
  place["samples"] = {64, 8};
  progress("placing the object (place.sketch)");
  execute(place);
  return session.last_ms();
}

// A row of the scene view across the object: the row of pixels (every 4th) with the most hits on it.
struct DragRow {
  std::vector<glm::dvec2> drag;  // pixels, top-left origin
  std::vector<double> ray_ms;    // one first-hit ray per pixel of the row
  double bvh_ms = 0;             // the caster's build over the placed object
};

DragRow find_drag_row(const core::SceneObject& placed, const core::Camera& view) {
  DragRow row;
  core::RayCaster caster;
  row.bvh_ms = bench_ms([&] {  // what the Press tool does when the object's world_mesh changed
    caster.add_mesh(*placed.world_mesh);
    caster.commit();
  });
  int best = 0;
  for (int y = 0; y < view.viewport.y; y += 8) {
    std::vector<double> xs;
    for (int x = 0; x < view.viewport.x; x += 4)
      if (caster.intersect(view.eye, view.ray_direction({x, y}))) xs.push_back(x);
    if (int(xs.size()) > best) {
      best = int(xs.size());
      row.drag.clear();
      for (double x = xs.front(); x <= xs.back(); x += 4) row.drag.push_back({x, double(y)});
    }
  }
  if (row.drag.size() < 2) throw std::runtime_error("bench press: the placed object is not in view");
  for (const glm::dvec2& px : row.drag)
    row.ray_ms.push_back(bench_ms([&] { (void)caster.intersect(view.eye, view.ray_direction(px)); }));
  return row;
}

// Milliseconds per run of the drags through the real Press tool, the path of the last, and the default radius.
struct ToolRuns {
  std::vector<double> first_hover, moves, after_release, commands, command_eval, radius_ms;
  std::vector<glm::dvec3> path;  // world units
  double radius = 0;             // world units
};

// `runs` drags along `drag`; the release runs lattice.press through the session (History), undone after each.
ToolRuns run_press_tool(EditorSession& session, const ui::MessageLog& messages, const core::Camera& view,
                        const std::vector<glm::dvec2>& drag, int runs) {
  ToolRuns t;
  std::string selected = "bunny";
  double command_ms = 0;
  ToolContext ctx{session, view, selected,
                  [&command_ms](std::string, std::function<void()> work) { command_ms = bench_ms(work); }, nullptr};
  PressTool tool;
  tool.activate(ctx);
  tool.set_object("bunny");
  tool.set_strength(kStrength);
  for (int r = 0; r < runs; ++r) {
    ToolInput in;
    in.mouse_px = drag.front();
    t.first_hover.push_back(bench_ms([&] { tool.handle_input(in, ctx); }));
    in.left_pressed = in.left_down = true;
    t.moves.push_back(bench_ms([&] { tool.handle_input(in, ctx); }));
    in.left_pressed = false;
    for (std::size_t i = 1; i < drag.size(); ++i) {
      in.mouse_px = drag[i];
      t.moves.push_back(bench_ms([&] { tool.handle_input(in, ctx); }));
    }
    t.path = tool.path();
    const std::size_t before = session.history().applied();
    in.left_down = false;
    in.left_released = true;
    command_ms = -1;
    tool.handle_input(in, ctx);
    if (command_ms < 0 || session.history().applied() != before + 1)
      throw std::runtime_error("bench press: the drag did not execute lattice.press: " +
                               (messages.messages().empty() ? "" : messages.messages().back().text));
    t.commands.push_back(command_ms);
    t.command_eval.push_back(session.history().at(before).stats().value("ms_evaluate", 0.0));
    in = ToolInput{};
    in.mouse_px = drag.front();
    t.after_release.push_back(bench_ms([&] { tool.handle_input(in, ctx); }));
    session.undo();
  }
  t.radius = tool.radius(ctx);
  // The default radius (0.1 × bounding-box diagonal), asked at every mouse move.
  for (int r = 0; r < std::max(3, runs); ++r) t.radius_ms.push_back(bench_ms([&] { (void)tool.radius(ctx); }));
  return t;
}

// (a) The pressed lattice per path prefix (#prefixes): lattice.press on a proxy object sharing obj's lattice and
// embedding, with 8 vertices; lattice_ms gets each command's milliseconds minus its evaluation.
std::vector<core::TrivariateBSpline<glm::dvec3>> pressed_lattices(const core::SceneObject& obj,
                                                                  const std::vector<glm::dvec3>& path,
                                                                  const std::vector<std::size_t>& prefixes,
                                                                  double radius, std::vector<double>& lattice_ms) {
  const core::FfdBinding& binding = *obj.ffd;
  core::Scene probe;
  {
    core::SceneObject proxy;
    proxy.name = "probe";
    proxy.source = "bench";
    auto corners = std::make_shared<core::TriMesh>();
    const core::Aabb box = core::mesh_bounds(obj.world_rest_mesh());
    for (int c = 0; c < 8; ++c)
      corners->positions.push_back(
          {c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z});
    corners->normals.assign(8, glm::dvec3(0.0, 1.0, 0.0));  // with normals: the same evaluation path as the object
    proxy.ffd = std::make_shared<const core::FfdBinding>(core::FfdBinding{
        binding.lattice, binding.embedding, core::embed_points(binding.embedding, corners->positions)});
    proxy.rest_mesh = std::move(corners);
    proxy.refresh();
    probe.insert(std::move(proxy));
  }
  std::vector<core::TrivariateBSpline<glm::dvec3>> lattices;
  for (std::size_t k : prefixes) {
    const std::vector<glm::dvec3> prefix(path.begin(), path.begin() + std::ptrdiff_t(k));
    core::CommandPtr cmd = CommandRegistry::builtin().parse(
        lattice_press_line({"probe", prefix, radius, kStrength, "smooth", false}), core::CommandContext{});
    const double ms = bench_ms([&] { cmd->redo(probe); });
    lattice_ms.push_back(std::max(0.0, ms - cmd->stats().value("ms_evaluate", 0.0)));
    lattices.push_back(probe.find("probe")->ffd->lattice);
    cmd->undo(probe);
  }
  return lattices;
}

// (b) Milliseconds per lattice of re-evaluating every vertex, positions + normals.
struct Reevaluation {
  json bind_ms = json::object();
  std::vector<double> fast_ms, read_ms, upload_ms, glsl_ms;  // upload and GLSL: with a GL context only
};

Reevaluation reevaluate(const core::SceneObject& obj, const std::vector<core::TrivariateBSpline<glm::dvec3>>& lattices,
                        bool gl, const std::function<void(const std::string&)>& progress) {
  const core::FfdBinding& binding = *obj.ffd;
  const std::vector<glm::dvec3> rest_normals = obj.world_rest_mesh().normals;
  Reevaluation e;
  {
    progress("cpu_fast re-evaluation");
    auto fast = core::make_cpu_ffd_evaluator(core::FfdBackend::cpu_fast);
    e.bind_ms["cpu_fast"] = bench_ms([&] { fast->bind_vertices(binding.params, rest_normals); });
    std::unique_ptr<gpu::MeshBuffers> buffers;
    if (gl) {
      buffers = std::make_unique<gpu::MeshBuffers>();
      buffers->upload(*obj.world_mesh);
    }
    std::vector<glm::vec3> p, n;  // float, as gpu::detail::FfdDisplay reads and uploads them
    for (const auto& lattice : lattices) {
      e.fast_ms.push_back(bench_ms([&] {
        fast->set_lattice(lattice, binding.embedding);
        fast->evaluate();
      }));
      e.read_ms.push_back(bench_ms([&] { fast->read_results_float(p, n); }));
      if (buffers)
        e.upload_ms.push_back(bench_ms([&] {
          buffers->update_vertices(p, n);
          glFinish();
        }));
    }
  }
  if (gl) {
    progress("glsl_compute re-evaluation");
    auto glsl = gpu::make_gl_ffd_evaluator(core::FfdBackend::glsl_compute);
    e.bind_ms["glsl_compute"] = bench_ms([&] {
      glsl->bind_vertices(binding.params, rest_normals);
      glFinish();
    });
    glsl->set_lattice(binding.lattice, binding.embedding);  // warm-up: shader compilation is not per update
    glsl->evaluate();
    glFinish();
    for (const auto& lattice : lattices)
      e.glsl_ms.push_back(bench_ms([&] {
        glsl->set_lattice(lattice, binding.embedding);
        glsl->evaluate();
        glFinish();
      }));
  }
  return e;
}

// The per-update table: tool move, (a), (b) per backend and the live previews they add up to, (c).
json per_update_stages(const ToolRuns& t, const std::vector<double>& lattice_ms, const Reevaluation& e, double cmd) {
  const double lat = bench_median(lattice_ms);
  json per_update = json::array();
  per_update.push_back(stage("Press tool per mouse move (ray cast + path)", bench_median(t.moves)));
  per_update.push_back(stage("(a) pressed lattice (lattice.press minus its evaluation)", lat));
  per_update.push_back(stage("(b) cpu_fast set_lattice + evaluate (positions + normals)", bench_median(e.fast_ms)));
  per_update.push_back(stage("    cpu_fast read-back to host arrays (float)", bench_median(e.read_ms)));
  std::vector<double> preview_fast;
  for (std::size_t i = 0; i < e.fast_ms.size(); ++i)
    preview_fast.push_back(lattice_ms[i] + e.fast_ms[i] + e.read_ms[i] + (e.upload_ms.empty() ? 0.0 : e.upload_ms[i]));
  if (!e.upload_ms.empty())
    per_update.push_back(stage("    cpu_fast upload (MeshBuffers::update_vertices)", bench_median(e.upload_ms)));
  per_update.push_back(stage(e.upload_ms.empty()
                                 ? "    live preview with cpu_fast: (a) + evaluate + read-back"
                                 : "    live preview with cpu_fast: (a) + evaluate + read-back + upload",
                             bench_median(preview_fast)));
  if (!e.glsl_ms.empty()) {
    per_update.push_back(stage("(b) glsl_compute set_lattice + evaluate + glFinish", bench_median(e.glsl_ms)));
    std::vector<double> preview_glsl;
    for (std::size_t i = 0; i < e.glsl_ms.size(); ++i) preview_glsl.push_back(lattice_ms[i] + e.glsl_ms[i]);
    per_update.push_back(stage("    live preview with glsl_compute: (a) + evaluate", bench_median(preview_glsl)));
  }
  per_update.push_back(stage("(c) lattice.press command at release (History::execute)", cmd));
  return per_update;
}

}  // namespace

int run_bench_press(const BenchPressOptions& o, std::ostream& out, std::ostream& err) {
  if (o.runs < 1) throw std::invalid_argument("bench press: --runs must be >= 1");
  if (o.vertices < 8) throw std::invalid_argument("bench press: --vertices must be >= 8");
  // Declared first so it outlives every GL evaluator and buffer below.
  std::string renderer;
  const std::unique_ptr<gpu::HeadlessContext> context = open_context(o.gpu, renderer, err);
  const std::function<void(const std::string&)> progress = [&err](const std::string& s) {
    err << "bench press: " << s << "\n" << std::flush;
  };

  json mesh_info;
  progress("building the mesh");
  core::TriMesh mesh = big_mesh(o, mesh_info);
  mesh_info["vertices"] = mesh.vertex_count();
  mesh_info["triangles"] = mesh.triangle_count();

  ui::MessageLog messages;
  EditorSession session(messages);  // no start(): no session log or lock
  const double place_ms = place_big_object(session, messages, std::move(mesh), mesh_info, progress);
  const core::SceneObject& placed = *session.scene().find("bunny");
  const glm::ivec3 counts = placed.ffd->lattice.control_counts(), orders = placed.ffd->lattice.orders();
  const core::Camera view = session.scene().camera;
  const DragRow row = find_drag_row(placed, view);

  progress("dragging the Press tool (" + std::to_string(o.runs) + " drag(s) of " + std::to_string(row.drag.size()) +
           " moves)");
  const ToolRuns t = run_press_tool(session, messages, view, row.drag, o.runs);

  // Per drag sample (path prefixes spread over the drag): what the live preview computes (Tool::live_preview +
  // the renderer's cpu_fast path: press_lattice, set_lattice + evaluate, float read-back, upload).
  const core::SceneObject& obj = *session.scene().find("bunny");
  std::vector<std::size_t> prefixes;
  for (int i = 0; i < o.runs; ++i)
    prefixes.push_back(o.runs == 1
                           ? t.path.size()
                           : 1 + std::size_t(std::lround(double(i) * double(t.path.size() - 1) / (o.runs - 1))));
  progress("lattice.press on the proxy (" + std::to_string(prefixes.size()) + " prefixes)");
  std::vector<double> lattice_ms;
  const auto lattices = pressed_lattices(obj, t.path, prefixes, t.radius, lattice_ms);
  const Reevaluation e = reevaluate(obj, lattices, context != nullptr, progress);

  const double cmd = bench_median(t.commands);
  const json per_update = per_update_stages(t, lattice_ms, e, cmd);
  json result = {
      {"bench", "press"},
      {"cpu", bench_cpu_model()},
      {"threads", tbb::info::default_concurrency()},
      {"renderer", renderer},
      {"runs", o.runs},
      {"mesh", mesh_info},
      {"lattice", {{"controls", {counts.x, counts.y, counts.z}}, {"order", {orders.x, orders.y, orders.z}}}},
      {"place_ms", place_ms},
      {"drag",
       {{"pixels", row.drag.size()}, {"samples", t.path.size()}, {"radius", t.radius}, {"strength", kStrength}}},
      {"tool",
       {{"first_hover_ms", bench_median(t.first_hover)},
        {"move_median_ms", bench_median(t.moves)},
        {"move_max_ms", *std::max_element(t.moves.begin(), t.moves.end())},
        {"hover_after_release_ms", bench_median(t.after_release)},
        {"bvh_build_ms", row.bvh_ms},
        {"ray_cast_ms", bench_median(row.ray_ms)},
        {"default_radius_ms", bench_median(t.radius_ms)}}},
      {"per_update", per_update},
      {"bind_ms", e.bind_ms},
      {"command",
       {{"median_ms", cmd},
        {"ms_evaluate", bench_median(t.command_eval)},
        {"updates_per_s", 1000.0 / cmd},
        {"interactive", 1000.0 / cmd >= kInteractive}}}};
  return bench_emit(result, o.json, out, print_press_table);
}

}  // namespace trispline::editor
