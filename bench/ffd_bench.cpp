// FFD throughput benchmark (numbers, not asserts). See ffd_bench.h.
#include "bench/ffd_bench.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <numbers>
#include <ostream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/ffd/ffd.h"
#include "core/ffd/ffd_evaluator.h"
#include "core/ffd/ffd_fast.h"
#include "core/mesh/bilinear_subdivision.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/uv_sphere.h"

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

}  // namespace

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

// Reference results of one (lattice, order, normals) case, and the figures every backend is compared with.
struct Reference {
  std::vector<glm::dvec3> positions, normals;
  double diagonal = 1.0;  // control-point bounding-box diagonal of the lattice
};

struct Errors {
  double rel = 0.0;         // max position error ÷ diagonal
  double normal_rad = 0.0;  // max angle between normals
};

Errors compare(const Reference& ref, const std::vector<glm::dvec3>& p, const std::vector<glm::dvec3>& n) {
  Errors e;
  if (p.size() != ref.positions.size()) return {std::numeric_limits<double>::infinity(), 0.0};
  double max_err = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) max_err = std::max(max_err, glm::length(ref.positions[i] - p[i]));
  e.rel = max_err / ref.diagonal;
  if (!ref.normals.empty()) {
    if (n.size() != ref.normals.size()) return {e.rel, std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i < n.size(); ++i)  // atan2(|a×b|, a·b): accurate for tiny angles, unlike acos(a·b)
      e.normal_rad = std::max(
          e.normal_rad, std::atan2(glm::length(glm::cross(ref.normals[i], n[i])), glm::dot(ref.normals[i], n[i])));
  }
  return e;
}

TriMesh benchmark_mesh(const FfdBenchOptions& o, nlohmann::json& mj) {
  TriMesh base;
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
  TriMesh mesh = subdivide_bilinear(base, o.subdivision_level);
  mj["subdivide_ms"] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  mj["base_vertices"] = base.positions.size();
  mj["vertices"] = mesh.positions.size();
  mj["triangles"] = mesh.triangles.size();
  mj["subdivision_level"] = o.subdivision_level;
  return mesh;
}

namespace {

// One lattice size and order, positions only then with normals: cpu_ref (the reference, `all` threads), cpu_fast on
// one and on `all` threads, each GL backend (kernel and end to end); one row per run appended to `cases`.
void run_case(const FfdBenchOptions& o, const TriMesh& mesh, const Embedding& emb,
              const std::vector<glm::dvec3>& params, int lat, int ord, int all, nlohmann::json& cases) {
  const std::vector<glm::dvec3> no_normals;
  const std::size_t nverts = mesh.positions.size();
  const auto mverts = [&](double ms) { return static_cast<double>(nverts) / (ms * 1e-3) * 1e-6; };
  const auto F = perturbed_lattice(emb, ord, lat, o.perturbation, o.seed);
  Aabb lb;
  for (const auto& p : F.control_points()) lb.extend(p);
  for (bool normals : {false, true}) {
    const std::vector<glm::dvec3>& rest_normals = normals ? mesh.normals : no_normals;
    const std::string what = std::to_string(lat) + "^3 lattice, order " + std::to_string(ord) +
                             (normals ? ", positions+normals" : ", positions");
    auto add = [&](FfdBackend b, int threads, const char* timing, double ms, const Errors& e) {
      cases.push_back({{"backend", to_string(b)},
                       {"threads", threads},
                       {"order", {ord, ord, ord}},
                       {"lattice", {lat, lat, lat}},
                       {"normals", normals},
                       {"vertices", nverts},
                       {"timing", timing},
                       {"median_ms", ms},
                       {"mverts_per_s", mverts(ms)},
                       {"max_err_rel", e.rel},
                       {"max_normal_err_rad", normals ? nlohmann::json(e.normal_rad) : nlohmann::json(nullptr)}});
    };
    auto timed_cpu = [&](FfdBackend b, int threads, Reference* ref_out, const Reference* ref) {
      if (o.progress) o.progress(std::string(to_string(b)) + ", " + std::to_string(threads) + " thread(s), " + what);
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      auto ev = make_cpu_ffd_evaluator(b);
      ev->bind_vertices(params, rest_normals);
      ev->set_lattice(F, emb);
      const double ms = median_ms(o.runs, [&] { ev->evaluate(); });
      std::vector<glm::dvec3> p, n;
      ev->read_results(p, n);
      if (ref_out) {
        ref_out->positions = std::move(p);
        ref_out->normals = std::move(n);
        ref_out->diagonal = lb.diagonal();
        add(b, threads, "kernel", ms, Errors{});
      } else {
        add(b, threads, "kernel", ms, compare(*ref, p, n));
      }
    };
    Reference ref;
    timed_cpu(FfdBackend::cpu_ref, all, &ref, nullptr);
    timed_cpu(FfdBackend::cpu_fast, 1, nullptr, &ref);
    if (all != 1) timed_cpu(FfdBackend::cpu_fast, all, nullptr, &ref);
    {
      // cpu_fast end to end on all threads, what a caller with new points pays: world points embedded, a fresh
      // evaluator bound (vertices sorted by lattice cell), evaluated, float64 results written (evaluate_into).
      if (o.progress) o.progress("cpu_fast end to end, " + what);
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(all));
      std::vector<double> p(3 * nverts), n(normals ? 3 * nverts : 0);
      const double e2e_ms = median_ms(o.runs, [&] {
        auto fresh = make_cpu_ffd_evaluator(FfdBackend::cpu_fast);
        fresh->bind_vertices(embed_points(emb, mesh.positions), rest_normals);
        fresh->set_lattice(F, emb);
        fresh->evaluate_into(glm::dvec3(0.0), p.data(), normals ? n.data() : nullptr);
      });
      std::vector<glm::dvec3> pv(nverts), nv(normals ? nverts : 0);
      std::memcpy(pv.data(), p.data(), p.size() * sizeof(double));
      if (normals) std::memcpy(nv.data(), n.data(), n.size() * sizeof(double));
      add(FfdBackend::cpu_fast, all, "end_to_end", e2e_ms, compare(ref, pv, nv));
    }

    for (const FfdBenchBackend& g : o.gpu_backends) {
      if (o.progress) o.progress(std::string(to_string(g.backend)) + ", " + what);
      auto ev = g.make();
      ev->bind_vertices(params, rest_normals);
      ev->set_lattice(F, emb);
      ev->evaluate();  // warm-up: shader JIT / first-use allocation are not what we measure
      g.finish();
      const double kernel_ms = median_ms(o.runs, [&] {
        ev->evaluate();
        g.finish();
      });
      std::vector<glm::dvec3> p, n;
      ev->read_results(p, n);
      add(g.backend, 0, "kernel", kernel_ms, compare(ref, p, n));
      const double e2e_ms = median_ms(o.runs, [&] {
        auto fresh = g.make();
        fresh->bind_vertices(params, rest_normals);
        fresh->set_lattice(F, emb);
        fresh->evaluate();
        fresh->read_results(p, n);
      });
      add(g.backend, 0, "end_to_end", e2e_ms, compare(ref, p, n));
    }
  }
}

}  // namespace

std::string bench_cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto p = line.find(':');
      return p == std::string::npos ? line : line.substr(p + 2);
    }
  return "unknown";
}

nlohmann::json run_ffd_benchmark(const FfdBenchOptions& o) {
  if (o.runs < 1) throw std::invalid_argument("ffd bench: runs must be >= 1");
  if (o.subdivision_level < 0) throw std::invalid_argument("ffd bench: subdivision level must be >= 0");
  if (o.lattices.empty() || o.orders.empty()) throw std::invalid_argument("ffd bench: no lattice sizes or orders");
  for (int lat : o.lattices)
    for (int ord : o.orders)
      if (ord < 2 || ord > lat)
        throw std::invalid_argument("ffd bench: order " + std::to_string(ord) + " must be in [2, lattice size " +
                                    std::to_string(lat) + "]");
  nlohmann::json out;
  out["renderer"] = o.renderer;
  out["gpu_shaders"] = o.gpu_shaders;

  nlohmann::json mj;
  const TriMesh mesh = benchmark_mesh(o, mj);
  const int all = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  out["cpu"] = bench_cpu_model();
  out["simd"] = ffd_fast_isa();
  out["threads_all"] = all;
  out["hardware_threads"] = std::thread::hardware_concurrency();
  out["runs"] = o.runs;
  out["mesh"] = mj;
  out["perturbation"] = o.perturbation;
  out["seed"] = o.seed;

  const Embedding emb = embed_bounding_box(mesh.positions, EmbeddingAxes{0, 1});
  const std::vector<glm::dvec3> params = embed_points(emb, mesh.positions);
  nlohmann::json cases = nlohmann::json::array();
  for (int lat : o.lattices)
    for (int ord : o.orders) run_case(o, mesh, emb, params, lat, ord, all, cases);
  out["cases"] = cases;
  return out;
}

void print_ffd_benchmark(const nlohmann::json& r, std::ostream& os) {
  const auto& m = r.at("mesh");
  os << "FFD benchmark on " << r.value("cpu", std::string("?")) << " (" << r.at("threads_all")
     << " threads, cpu_fast kernel: " << r.value("simd", std::string("?"))
     << "), GL: " << r.value("renderer", std::string("none")) << "\n";
  if (m.at("fallback").get<bool>()) os << "NOTE: " << m.at("note").get<std::string>() << "\n";
  os << "mesh: " << m.at("source").get<std::string>() << ", " << m.at("base_vertices") << " vertices -> "
     << m.at("vertices") << " vertices, " << m.at("triangles") << " triangles (OpenSubdiv bilinear level "
     << m.at("subdivision_level") << "); median of " << r.at("runs") << " runs\n\n";
  os << std::left << std::setw(9) << "lattice" << std::setw(7) << "order" << std::setw(11) << "output" << std::setw(14)
     << "backend" << std::setw(9) << "threads" << std::setw(12) << "timing" << std::right << std::setw(10) << "ms"
     << std::setw(13) << "Mverts/s" << std::setw(13) << "err_rel" << std::setw(13) << "normal_rad"
     << "\n";
  for (const auto& e : r.at("cases")) {
    std::ostringstream ms, rate, err, nerr;
    ms << std::fixed << std::setprecision(2) << e.at("median_ms").get<double>();
    rate << std::fixed << std::setprecision(1) << e.at("mverts_per_s").get<double>();
    err << std::scientific << std::setprecision(2) << e.at("max_err_rel").get<double>();
    if (e.at("max_normal_err_rad").is_null())
      nerr << "-";
    else
      nerr << std::scientific << std::setprecision(2) << e.at("max_normal_err_rad").get<double>();
    const int l = e.at("lattice")[0].get<int>();
    os << std::left << std::setw(9) << (std::to_string(l) + "^3") << std::setw(7) << e.at("order")[0].get<int>()
       << std::setw(11) << (e.at("normals").get<bool>() ? "pos+nrm" : "pos") << std::setw(14)
       << e.at("backend").get<std::string>() << std::setw(9) << e.at("threads").get<int>() << std::setw(12)
       << e.at("timing").get<std::string>() << std::right << std::setw(10) << ms.str() << std::setw(13) << rate.str()
       << std::setw(13) << err.str() << std::setw(13) << nerr.str() << "\n";
  }
  os << "\nerr_rel: max position error vs cpu_ref / lattice bbox diagonal; normal_rad: max normal angle vs cpu_ref.\n";
}

}  // namespace trispline::core
