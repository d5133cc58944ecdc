// FFD throughput benchmark (numbers, not asserts). See ffd_bench.h.
#include "core/deform/ffd_bench.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/deform/ffd.h"
#include "core/deform/ffd_fast.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {

namespace {

using Clock = std::chrono::steady_clock;

double median_ms(int runs, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const auto a = Clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t.size() % 2 ? t[t.size() / 2] : 0.5 * (t[t.size() / 2 - 1] + t[t.size() / 2]);
}

// Lattice of `controls`³ control points over the embedded box: the identity (Greville abscissae mapped back to
// world space) plus a uniform random displacement of ±perturbation × cell size per coordinate.
TrivariateBSpline<glm::dvec3> perturbed_lattice(const Embedding& e, int order, int controls, double perturbation,
                                                std::uint32_t seed) {
  const KnotVector kv = KnotVector::clamped_uniform(order, controls);
  const std::vector<double> g = kv.greville();
  const glm::dmat3 inv = glm::inverse(e.linear);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<glm::dvec3> cps;
  const double cell = perturbation / (controls - 1);
  for (int k = 0; k < controls; ++k)
    for (int j = 0; j < controls; ++j)
      for (int i = 0; i < controls; ++i) {
        glm::dvec3 q(g[i], g[j], g[k]);
        q += cell * glm::dvec3(uni(rng), uni(rng), uni(rng));
        cps.push_back(inv * (q - e.offset));
      }
  return TrivariateBSpline<glm::dvec3>(kv, kv, kv, std::move(cps));
}

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto p = line.find(':');
      return p == std::string::npos ? line : line.substr(p + 2);
    }
  return "unknown";
}

}  // namespace

nlohmann::json run_ffd_benchmark(const FfdBenchOptions& o) {
  if (o.runs < 1) throw std::invalid_argument("ffd bench: runs must be >= 1");
  if (o.subdivision_level < 0) throw std::invalid_argument("ffd bench: subdivision level must be >= 0");
  for (int ord : o.orders)
    if (ord < 2 || ord > o.controls)
      throw std::invalid_argument("ffd bench: order " + std::to_string(ord) +
                                  " must be in [2, controls = " + std::to_string(o.controls) + "]");
  nlohmann::json out;
  out["benchmark"] = "ffd";

  // Mesh: the bunny, or a sphere of similar vertex count when the file is not there.
  TriMesh base;
  nlohmann::json mj;
  if (std::filesystem::exists(o.mesh_path)) {
    base = load_mesh(o.mesh_path);
    mj["source"] = o.mesh_path;
    mj["fallback"] = false;
    mj["note"] = "";
  } else {
    base = make_uv_sphere(1.0, 130, 268);
    mj["source"] = "generated sphere (130 x 268)";
    mj["fallback"] = true;
    mj["note"] = "mesh file '" + o.mesh_path + "' not found; using a generated sphere instead";
  }
  const auto t0 = Clock::now();
  const TriMesh mesh = subdivide_bilinear(base, o.subdivision_level);
  mj["subdivide_ms"] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  mj["base_vertices"] = base.positions.size();
  mj["vertices"] = mesh.positions.size();
  mj["triangles"] = mesh.triangles.size();
  mj["subdivision_level"] = o.subdivision_level;
  out["mesh"] = mj;
  out["lattice"] = {{"controls", o.controls}, {"perturbation", o.perturbation}, {"seed", o.seed}};

  const int all = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  out["threads_all"] = all;
  out["hardware_threads"] = std::thread::hardware_concurrency();
  out["cpu"] = cpu_model();
  out["runs"] = o.runs;

  const Embedding emb = embed_bounding_box(mesh.positions, EmbeddingAxes{0, 1});
  const std::vector<glm::dvec3> params = embed_points(emb, mesh.positions);
  const FloatSoA3 params_f = FloatSoA3::from(params);
  const FloatSoA3 normals_f = FloatSoA3::from(mesh.normals);
  const double nverts = static_cast<double>(mesh.positions.size());

  nlohmann::json results = nlohmann::json::array(), accuracy = nlohmann::json::array();
  for (int ord : o.orders) {
    const auto F = perturbed_lattice(emb, ord, o.controls, o.perturbation, o.seed);
    const FfdFastLattice fast(F, emb);
    Aabb lb;
    for (const auto& p : F.control_points()) lb.extend(p);
    for (bool normals : {false, true}) {
      std::vector<glm::dvec3> ref_p, ref_n;
      FloatSoA3 fp, fn;
      for (int threads : {1, all}) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        const double ref_ms = median_ms(o.runs, [&] {
          if (normals)
            ffd_evaluate(F, emb, params, mesh.normals, ref_p, ref_n);
          else
            ffd_evaluate(F, params, ref_p);
        });
        const double fast_ms = median_ms(o.runs, [&] {
          if (normals)
            ffd_evaluate_fast(fast, params_f, normals_f, fp, fn);
          else
            ffd_evaluate_fast(fast, params_f, fp);
        });
        for (auto [path, ms] : {std::pair{"reference_double", ref_ms}, std::pair{"fast_float", fast_ms}})
          results.push_back({{"order", ord},
                             {"normals", normals},
                             {"threads", threads},
                             {"path", path},
                             {"median_ms", ms},
                             {"vertices_per_second", nverts / (ms * 1e-3)}});
      }
      double max_err = 0.0, max_ang = 0.0;
      for (std::size_t i = 0; i < ref_p.size(); ++i) {
        max_err = std::max(max_err, glm::length(ref_p[i] - glm::dvec3(fp.x[i], fp.y[i], fp.z[i])));
        if (normals) {
          // atan2(|a×b|, a·b): accurate for tiny angles (acos(a·b) is not, and float normals are unit only to ~1e-7)
          const glm::dvec3 f(fn.x[i], fn.y[i], fn.z[i]);
          const double ang = std::atan2(glm::length(glm::cross(ref_n[i], f)), glm::dot(ref_n[i], f));
          max_ang = std::max(max_ang, ang * 180.0 / std::numbers::pi);
        }
      }
      accuracy.push_back({{"order", ord},
                          {"normals", normals},
                          {"max_position_error", max_err},
                          {"relative_position_error", max_err / lb.diagonal()},
                          {"max_normal_angle_deg", normals ? nlohmann::json(max_ang) : nlohmann::json(nullptr)}});
    }
  }
  out["results"] = results;
  out["accuracy"] = accuracy;
  return out;
}

void print_ffd_benchmark(const nlohmann::json& r, std::ostream& os) {
  const auto& m = r.at("mesh");
  os << "FFD benchmark on " << r.value("cpu", std::string("?")) << " (" << r.at("threads_all") << " threads)\n";
  if (m.at("fallback").get<bool>()) os << "NOTE: " << m.at("note").get<std::string>() << "\n";
  os << "mesh: " << m.at("source").get<std::string>() << ", " << m.at("base_vertices") << " vertices -> "
     << m.at("vertices") << " vertices, " << m.at("triangles") << " triangles (OpenSubdiv bilinear level "
     << m.at("subdivision_level") << ")\n";
  os << "lattice: " << r.at("lattice").at("controls") << "^3 controls, perturbation "
     << r.at("lattice").at("perturbation") << "; median of " << r.at("runs") << " runs\n\n";
  os << std::left << std::setw(7) << "order" << std::setw(18) << "output" << std::setw(9) << "threads" << std::setw(18)
     << "path" << std::right << std::setw(11) << "ms" << std::setw(16) << "Mvertices/s\n";
  for (const auto& e : r.at("results")) {
    std::ostringstream ms, rate;
    ms << std::fixed << std::setprecision(2) << e.at("median_ms").get<double>();
    rate << std::fixed << std::setprecision(2) << e.at("vertices_per_second").get<double>() * 1e-6;
    os << std::left << std::setw(7) << e.at("order").get<int>() << std::setw(18)
       << (e.at("normals").get<bool>() ? "positions+normals" : "positions") << std::setw(9)
       << e.at("threads").get<int>() << std::setw(18) << e.at("path").get<std::string>() << std::right << std::setw(11)
       << ms.str() << std::setw(15) << rate.str() << "\n";
  }
  os << "\nfast float vs reference double:\n";
  for (const auto& a : r.at("accuracy")) {
    os << "  order " << a.at("order").get<int>() << (a.at("normals").get<bool>() ? " positions+normals" : " positions")
       << ": max position error " << a.at("max_position_error").get<double>() << " ("
       << a.at("relative_position_error").get<double>() << " of lattice diagonal)";
    if (!a.at("max_normal_angle_deg").is_null())
      os << ", max normal angle " << a.at("max_normal_angle_deg").get<double>() << " deg";
    os << "\n";
  }
}

}  // namespace trispline::core
