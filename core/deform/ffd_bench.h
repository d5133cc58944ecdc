// trispline::core FFD benchmark — the figures behind `trispline bench ffd` (docs/performance.md).
//
// Measures CPU FFD throughput (vertices/second, median of several runs) on a big mesh: the Stanford bunny (or a
// generated sphere when the file is absent) refined uniformly with OpenSubdiv Far (bilinear scheme, level 2 by
// default: the 34,835-vertex bunny becomes ~0.8 M vertices), deformed by a randomly perturbed 4×4×4 lattice
// (clamped uniform knots), for every combination of
//   order 3 (tri-quadratic) and 4 (tri-cubic) × positions only / positions + normals ×
//   1 thread / all threads (tbb::global_control) × reference double (ffd_evaluate) / fast float (ffd_evaluate_fast),
// plus the maximum error of the fast path against the reference. Numbers, never asserts. Pure core: no GL.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct FfdBenchOptions {
  std::string mesh_path = "assets/data/bunny.obj";  // any load_mesh format; a sphere is generated if absent
  int subdivision_level = 2;                        // OpenSubdiv bilinear uniform refinement level (0 = none)
  int controls = 4;                                 // lattice control count per axis
  std::vector<int> orders{3, 4};                    // orders (= degree + 1) to measure; each ≤ controls
  double perturbation = 0.15;                       // random control displacement, fraction of the lattice cell
  std::uint32_t seed = 1;                           // std::mt19937 seed for the perturbation
  int runs = 5;                                     // timed runs per configuration (median reported), ≥ 1
  int threads = 0;                                  // "all threads" count; 0 = tbb default concurrency
};

// Runs the benchmark. Result (JSON object):
//   mesh     {source, fallback (bool), note, base_vertices, vertices, triangles, subdivision_level, subdivide_ms}
//   lattice  {controls, perturbation, seed}
//   threads_all, hardware_threads, runs
//   results  [{order, normals (bool), threads, path ("reference_double" | "fast_float"), median_ms,
//              vertices_per_second}]
//   accuracy [{order, normals, max_position_error (world units), relative_position_error (÷ lattice bbox
//              diagonal), max_normal_angle_deg}]
// Throws std::invalid_argument on bad options (order < 2 or > controls, runs < 1, level < 0).
nlohmann::json run_ffd_benchmark(const FfdBenchOptions& options);

// Human-readable table of a run_ffd_benchmark result.
void print_ffd_benchmark(const nlohmann::json& result, std::ostream& out);

// Uniform refinement with OpenSubdiv Far (bilinear scheme, Far::PrimvarRefiner for positions); quads are split
// into two triangles (a,b,c), (a,c,d); normals recomputed (area-weighted), uvs dropped. level 0 returns a copy.
TriMesh subdivide_bilinear(const TriMesh& mesh, int level);

// Triangulated UV sphere of `radius` with `rings` latitude bands and `segments` longitude bands (poles shared).
TriMesh make_uv_sphere(double radius, int rings, int segments);

}  // namespace trispline::core
