// `trispline bench ffd` — runs core::run_ffd_benchmark with the GPU backends added when a headless GL context can
// be made (EGL: llvmpipe here, NVIDIA's EGL on the device machine). Prints a table or one JSON object.
#pragma once

#include <iosfwd>
#include <string>

namespace trispline::editor {

struct BenchFfdOptions {
  std::string mesh_path;             // empty: assets/data/bunny.obj, subdivided to level 2 (~0.8 M vertices)
  int subdivision = -1;              // OpenSubdiv bilinear levels; -1 = 2 for the default mesh, 0 for --mesh
  int runs = 5;                      // timed runs per case (median)
  bool json = false;                 // one JSON object on `out` instead of a table
  bool gpu = true;                   // add glsl_compute and glsl_vertex (needs a GL 4.3 context)
  std::string gpu_shaders = "auto";  // "auto" | "specialised" | "generic" (gpu::FfdOrderMode)
};

// Returns the process exit code (0). Progress lines go to `err`; a GL context that cannot be made is reported in
// the result's "renderer" field and on `err`, and the CPU cases still run. Throws std::invalid_argument on bad
// options.
int run_bench_ffd(const BenchFfdOptions& options, std::ostream& out, std::ostream& err);

}  // namespace trispline::editor
