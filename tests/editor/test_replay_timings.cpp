// `trispline replay`: report.json carries the timing overlay's numbers (per-command stage timings, the
// final render's FFD / draw passes, the timer method), `--ffd-backend` renders and exports through the chosen
// evaluator (a GLSL backend's scene.glb is read back from the GPU and must match the CPU reference), `--time`
// moves animated objects, and bad options fail with a clear message. GL runs for real on llvmpipe (EGL).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/gltf_io.h"
#include "editor/cli/cli.h"
#include "editor/replay/replay.h"
#include "gpu/gl/timer.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path source(const std::string& rel) { return fs::path(TRISPLINE_SOURCE_DIR) / rel; }
fs::path out_dir(const std::string& name) {
  const fs::path out = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "replay_timings" / name;
  fs::remove_all(out);
  return out;
}

nlohmann::json read_report(const fs::path& dir) {
  std::ifstream in(dir / "report.json");
  EXPECT_TRUE(in.good()) << dir;
  return nlohmann::json::parse(in);
}

// Runs the CLI in-process with `args` after "trispline"; returns the exit code, stderr in *err.
int cli(std::vector<std::string> args, std::string* err = nullptr) {
  args.insert(args.begin(), "trispline");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  testing::internal::CaptureStderr();
  const int rc = editor::run_cli(int(argv.size()), argv.data());
  const std::string e = testing::internal::GetCapturedStderr();
  if (err) *err = e;
  return rc;
}

int replay(const fs::path& log, const fs::path& out, core::FfdBackend backend, double time_s = 0, bool render = false) {
  editor::ReplayOptions o;
  o.log = log;
  o.out_dir = out;
  o.ffd_backend = backend;
  o.time_s = time_s;
  o.render = render;
  o.width = 160;
  o.height = 120;
  return editor::run_replay(o);
}

struct Diff {
  double max_position = 0;    // world units
  double max_normal_rad = 0;  // angle
  double scene_size = 0;      // bounding-box diagonal of the reference
};

// Compares two scene.glb files object by object (same names, order, vertex counts).
Diff compare_glb(const fs::path& reference, const fs::path& other) {
  const auto a = core::read_gltf_objects(reference), b = core::read_gltf_objects(other);
  Diff d;
  EXPECT_EQ(a.size(), b.size());
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& o : a)
    for (const auto& p : o.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  d.scene_size = glm::length(hi - lo);
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    const auto &pa = a[i].mesh.positions, &pb = b[i].mesh.positions;
    EXPECT_EQ(pa.size(), pb.size()) << a[i].name;
    if (pa.size() != pb.size()) continue;
    for (std::size_t v = 0; v < pa.size(); ++v) d.max_position = std::max(d.max_position, glm::length(pa[v] - pb[v]));
    const auto &na = a[i].mesh.normals, &nb = b[i].mesh.normals;
    EXPECT_EQ(na.size(), nb.size()) << a[i].name;
    if (na.size() != nb.size()) continue;
    for (std::size_t v = 0; v < na.size(); ++v) {
      const double c = glm::dot(glm::normalize(na[v]), glm::normalize(nb[v]));
      d.max_normal_rad = std::max(d.max_normal_rad, std::acos(std::clamp(c, -1.0, 1.0)));
    }
  }
  return d;
}

bool positions_differ(const fs::path& a, const fs::path& b, const std::string& object) {
  for (const auto& x : core::read_gltf_objects(a))
    for (const auto& y : core::read_gltf_objects(b))
      if (x.name == object && y.name == object) return x.mesh.positions != y.mesh.positions;
  ADD_FAILURE() << object << " missing";
  return false;
}

}  // namespace

TEST(ReplayTimings, ReportCarriesTheOverlayNumbers) {
  const fs::path out = out_dir("report");
  ASSERT_EQ(replay(source("tests/logs/place_on_plane.jsonl"), out, core::FfdBackend::glsl_compute, 0, true), 0);
  const nlohmann::json report = read_report(out);
  EXPECT_EQ(report.at("ffd_backend"), "glsl_compute");
  const nlohmann::json& t = report.at("timings");

  bool saw_placement = false;
  for (const auto& c : t.at("commands")) {
    EXPECT_GE(c.at("total_ms").get<double>(), 0.0);
    if (c.at("cmd") != "place.sketch") continue;
    saw_placement = true;
    const auto& stages = c.at("stages_ms");
    for (const char* s : {"fit", "rays", "surface", "volume", "embed", "evaluate"}) {
      ASSERT_TRUE(stages.contains(s)) << s;
      EXPECT_GT(stages.at(s).get<double>(), 0.0) << s;
    }
    EXPECT_GT(c.at("total_ms").get<double>(), stages.at("rays").get<double>());
  }
  EXPECT_TRUE(saw_placement);

  const nlohmann::json& r = t.at("render");
  EXPECT_EQ(r.at("ffd_backend"), "glsl_compute");
  EXPECT_EQ(r.at("ffd_backend_label"), "GLSL compute");
  EXPECT_EQ(r.at("renderer"), report.at("renderer"));
  EXPECT_GE(r.at("ffd_ms").get<double>(), 0.0);
  EXPECT_GE(r.at("draw_ms").get<double>(), 0.0);
  EXPECT_GT(r.at("ffd_objects").get<int>(), 0);
  EXPECT_GT(r.at("ffd_vertices").get<std::size_t>(), 0u);
  EXPECT_GT(r.at("vertices_per_second").get<double>(), 0.0);
  const std::string renderer = r.at("renderer");
  const bool software =
      renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
  EXPECT_EQ(r.at("timer_mode"), gpu::GpuTimer::describe(software ? gpu::GpuTimer::Mode::wall_clock_finish
                                                                 : gpu::GpuTimer::Mode::timer_query));
  EXPECT_EQ(t.at("geometry").at("source"), "glsl_compute");
  EXPECT_GT(t.at("geometry").at("vertices").get<std::size_t>(), 0u);
  std::printf("render: %s\n", r.dump().c_str());

  // The default backend (CPU reference) reports the same schema.
  const fs::path ref = out_dir("report_ref");
  ASSERT_EQ(replay(source("tests/logs/place_on_plane.jsonl"), ref, core::FfdBackend::cpu_ref, 0, true), 0);
  const nlohmann::json rr = read_report(ref).at("timings");
  EXPECT_EQ(rr.at("render").at("ffd_backend"), "cpu_ref");
  EXPECT_GE(rr.at("render").at("draw_ms").get<double>(), 0.0);
  EXPECT_FALSE(rr.at("render").at("timer_mode").get<std::string>().empty());
  EXPECT_EQ(rr.at("geometry").at("source"), "cpu_ref");
}

TEST(ReplayTimings, GlslScenesMatchTheCpuReference) {
  for (const char* log : {"assets/scenes/default.jsonl", "tests/logs/gpu_ffd_orders.jsonl"}) {
    const fs::path ref = out_dir("ref");
    ASSERT_EQ(replay(source(log), ref, core::FfdBackend::cpu_ref), 0) << log;
    for (core::FfdBackend b :
         {core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex, core::FfdBackend::cpu_fast}) {
      const fs::path out = out_dir(core::to_string(b));
      ASSERT_EQ(replay(source(log), out, b), 0) << log << " " << core::to_string(b);
      EXPECT_EQ(read_report(out).at("timings").at("geometry").at("source"), core::to_string(b));
      const Diff d = compare_glb(ref / "scene.glb", out / "scene.glb");
      EXPECT_GT(d.scene_size, 0.0);
      EXPECT_LE(d.max_position, 1e-5 * d.scene_size) << log << " " << core::to_string(b);
      EXPECT_LE(d.max_normal_rad, 1e-3) << log << " " << core::to_string(b);
      std::printf("%s %s: max position error %.3g (%.3g of the scene), max normal error %.3g rad\n", log,
                  core::to_string(b), d.max_position, d.max_position / d.scene_size, d.max_normal_rad);
    }
  }
}

TEST(ReplayTimings, CliRunsTheGpuPathEndToEnd) {
  const fs::path gpu = out_dir("cli_gpu"), ref = out_dir("cli_ref");
  const std::string log = source("tests/logs/gpu_ffd_orders.jsonl").string();
  ASSERT_EQ(
      cli({"replay", log, "--out", gpu.string(), "--ffd-backend", "glsl_compute", "--width", "160", "--height", "120"}),
      0);
  ASSERT_EQ(cli({"replay", log, "--out", ref.string(), "--no-render"}), 0);
  EXPECT_EQ(read_report(ref).at("ffd_backend"), "cpu_ref") << "the default backend";
  EXPECT_TRUE(fs::exists(gpu / "final.png"));
  const Diff d = compare_glb(ref / "scene.glb", gpu / "scene.glb");
  EXPECT_LE(d.max_position, 1e-5 * d.scene_size);
}

TEST(ReplayTimings, TimeMovesAnimatedObjectsOnEveryBackend) {
  const fs::path log = source("tests/logs/ring_animate.jsonl");
  const fs::path t0 = out_dir("t0"), t25 = out_dir("t2.5"), t10 = out_dir("t10"), gpu = out_dir("t2.5_gpu");
  ASSERT_EQ(replay(log, t0, core::FfdBackend::cpu_ref, 0), 0);
  ASSERT_EQ(replay(log, t25, core::FfdBackend::cpu_ref, 2.5), 0);
  ASSERT_EQ(replay(log, t10, core::FfdBackend::cpu_ref, 10.0), 0);  // velocity 0.1/s: one full turn
  ASSERT_EQ(replay(log, gpu, core::FfdBackend::glsl_compute, 2.5, true), 0);
  EXPECT_EQ(read_report(t25).at("time_s").get<double>(), 2.5);
  EXPECT_TRUE(positions_differ(t0 / "scene.glb", t25 / "scene.glb", "t1"));
  EXPECT_FALSE(positions_differ(t0 / "scene.glb", t25 / "scene.glb", "ground")) << "not animated";
  const Diff turn = compare_glb(t0 / "scene.glb", t10 / "scene.glb");
  EXPECT_LE(turn.max_position, 1e-6 * turn.scene_size) << "cpu_ref: a full period (t = 10 s) returns to t = 0";
  const fs::path g0 = out_dir("t0_gpu"), g10 = out_dir("t10_gpu");
  ASSERT_EQ(replay(log, g0, core::FfdBackend::glsl_compute, 0), 0);
  ASSERT_EQ(replay(log, g10, core::FfdBackend::glsl_compute, 10.0), 0);
  const Diff gturn = compare_glb(g0 / "scene.glb", g10 / "scene.glb");
  EXPECT_LE(gturn.max_position, 1e-5 * gturn.scene_size) << "glsl_compute: a full period returns to the start";
  const Diff d = compare_glb(t25 / "scene.glb", gpu / "scene.glb");
  EXPECT_LE(d.max_position, 1e-5 * d.scene_size);
  EXPECT_EQ(read_report(gpu).at("timings").at("render").at("time_s").get<double>(), 2.5);
}

TEST(ReplayTimings, BadOptionsFailWithAClearMessage) {
  const std::string log = source("tests/logs/place_on_plane.jsonl").string();
  const fs::path out = out_dir("bad");
  std::string err;
  EXPECT_NE(cli({"replay", log, "--out", out.string(), "--ffd-backend", "cuda"}, &err), 0);
  EXPECT_NE(err.find("unknown FFD backend 'cuda'"), std::string::npos) << err;
  EXPECT_NE(err.find("glsl_compute"), std::string::npos) << "lists the valid names: " << err;
  EXPECT_NE(cli({"replay", log, "--out", out.string(), "--ffd-backend"}, &err), 0);
  EXPECT_NE(cli({"replay", log, "--out", out.string(), "--ffd-backend", "GLSL_COMPUTE"}, &err), 0);
  for (const char* t : {"nan", "inf", "soon", "1.5s"}) {
    EXPECT_NE(cli({"replay", log, "--out", out.string(), "--time", t}, &err), 0) << t;
    EXPECT_NE(err.find("--time needs a finite number of seconds"), std::string::npos) << t << ": " << err;
  }
  EXPECT_FALSE(fs::exists(out / "report.json")) << "nothing ran";
  // A valid negative time is fine (the objects run backwards).
  EXPECT_EQ(cli({"replay", log, "--out", out.string(), "--time", "-1.5", "--no-render"}, &err), 0) << err;
}
