// trispline::core FFD benchmark — the figures behind `trispline bench ffd` (docs/performance.md).
//
// Measures FFD throughput (vertices/second, median of several runs) of every evaluator backend (ffd_evaluator.h) on
// a big mesh: the Stanford bunny (or a generated sphere when the file is absent) refined uniformly with OpenSubdiv
// Far (bilinear scheme, level 2 by default: the 34,835-vertex bunny becomes 835,994 vertices), embedded in its
// bounding box and deformed by randomly perturbed L×L×L lattices (clamped uniform knot vectors), for every
//   lattice size (4 and 8) × order (3 = tri-quadratic, 4 = tri-cubic) × positions only / positions + normals
// and every backend: cpu_ref (all threads), cpu_fast (1 thread and all threads), and the GPU backends the caller
// passes in (core has no GL; bench/bench_ffd.cpp adds glsl_compute and glsl_vertex when a context can be made),
// each timed twice: "kernel" (evaluate() and, for the GPU, glFinish) and "end_to_end" (upload of the per-vertex
// data and the lattice, evaluation, read-back to host memory). Every backend's result is compared with cpu_ref:
// max_err_rel = max position error ÷ the lattice's control-point bounding-box diagonal, max_normal_err_rad = the
// largest angle between normals. Numbers, never asserts.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// A backend the benchmark cannot make itself (the GPU ones).
struct FfdBenchBackend {
  FfdBackend backend = FfdBackend::glsl_compute;
  std::function<std::unique_ptr<FfdEvaluator>()> make;  // a fresh evaluator
  std::function<void()> finish;                         // waits until issued work is done (glFinish)
};

struct FfdBenchOptions {
  std::string mesh_path = "assets/data/bunny.obj";   // any load_mesh format; a sphere is generated if absent
  int subdivision_level = 2;                         // OpenSubdiv bilinear uniform refinement level (0 = none)
  std::vector<int> lattices{4, 8};                   // control points per axis (L×L×L lattices)
  std::vector<int> orders{3, 4};                     // orders (= degree + 1) to measure; each ≤ every lattice size
  double perturbation = 0.15;                        // random control displacement, fraction of the lattice cell
  std::uint32_t seed = 1;                            // std::mt19937 seed for the perturbation
  int runs = 5;                                      // timed runs per configuration (median reported), ≥ 1
  int threads = 0;                                   // "all threads" count; 0 = tbb default concurrency
  std::string renderer = "none";                     // GL_RENDERER of the GPU backends' context, or why there is none
  std::string gpu_shaders;                           // how the GPU backends' shaders get the orders (reported)
  std::vector<FfdBenchBackend> gpu_backends;         // measured after the CPU backends
  std::function<void(const std::string&)> progress;  // called before each case (a line of text); may be empty
};

// Runs the benchmark. Result (one JSON object, the `bench ffd --json` output):
//   renderer, gpu_shaders, cpu, simd (the cpu_fast kernel's instruction set), threads_all, hardware_threads, runs,
//   mesh {source, fallback, note, base_vertices, vertices, triangles, subdivision_level, subdivide_ms},
//   perturbation, seed,
//   cases [{backend ("cpu_ref" | "cpu_fast" | "glsl_compute" | "glsl_vertex"), threads (CPU threads; 0 for GPU
//           backends), order [o,o,o], lattice [l,m,n], normals, vertices, timing ("kernel" | "end_to_end"),
//           median_ms, mverts_per_s, max_err_rel, max_normal_err_rad (null without normals)}]
// Throws std::invalid_argument on bad options (order < 2 or > a lattice size, runs < 1, level < 0).
nlohmann::json run_ffd_benchmark(const FfdBenchOptions& options);

// Human-readable table of a run_ffd_benchmark result.
void print_ffd_benchmark(const nlohmann::json& result, std::ostream& out);

// The benchmark mesh: o.mesh_path (the bunny), or a generated sphere of similar vertex count when the file is not
// there, refined to o.subdivision_level. mj gets its source, fallback note, counts and subdivision time.
TriMesh benchmark_mesh(const FfdBenchOptions& o, nlohmann::json& mj);

// Lattice of controls³ control points (order per axis) over the box embedded by e: the identity (Greville abscissae
// mapped back to world space) plus a uniform random displacement of ±perturbation × cell size per coordinate.
TrivariateBSpline<glm::dvec3> perturbed_lattice(const Embedding& e, int order, int controls, double perturbation,
                                                std::uint32_t seed);

// "model name" of /proc/cpuinfo, or "unknown": the "cpu" of every benchmark's result.
std::string bench_cpu_model();

}  // namespace trispline::core
