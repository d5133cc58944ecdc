#include "bench/bench_ffd.h"

#include <epoxy/gl.h>

#include <iostream>
#include <memory>

#include "bench/ffd_bench.h"
#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/gl_context.h"

namespace trispline::editor {

int run_bench_ffd(const BenchFfdOptions& options, std::ostream& out, std::ostream& err) {
  // Declared first so it outlives `o`: the GPU backends' shared program cache deletes GL programs when destroyed.
  std::unique_ptr<gpu::HeadlessContext> context;
  core::FfdBenchOptions o;
  if (!options.mesh_path.empty()) o.mesh_path = options.mesh_path;
  o.subdivision_level = options.subdivision >= 0 ? options.subdivision : (options.mesh_path.empty() ? 2 : 0);
  o.runs = options.runs;
  o.progress = [&err](const std::string& line) { err << "bench ffd: " << line << "\n" << std::flush; };

  if (options.gpu) {
    try {
      context = std::make_unique<gpu::HeadlessContext>();
      o.renderer = context->renderer();
      // One program cache for all evaluators: "end_to_end" makes a fresh evaluator per run, and llvmpipe would
      // otherwise JIT-compile the program again each time (about a second), which is not what we measure.
      auto programs = std::make_shared<gpu::FfdProgramCache>();
      const gpu::FfdOrderMode mode = options.gpu_shaders == "specialised" ? gpu::FfdOrderMode::specialised
                                     : options.gpu_shaders == "generic"   ? gpu::FfdOrderMode::generic
                                                                          : gpu::FfdOrderMode::automatic;
      const bool specialised = mode == gpu::FfdOrderMode::specialised ||
                               (mode == gpu::FfdOrderMode::automatic && !gpu::is_software_renderer());
      o.gpu_shaders = specialised ? "order-specialised (ORDER_U/V/W defines, unrolled loops)"
                                  : "generic orders (one program for all orders, read from the knot tables)";
      for (core::FfdBackend b : {core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex})
        o.gpu_backends.push_back(
            {b, [b, programs, mode] { return gpu::make_gl_ffd_evaluator(b, programs, mode); }, [] { glFinish(); }});
    } catch (const gpu::GlContextError& e) {
      o.renderer = std::string("none (no GL context: ") + e.what() + ")";
      err << "bench ffd: no GL context, GPU backends skipped: " << e.what() << "\n";
    }
  } else {
    o.renderer = "none (--cpu-only)";
  }
  const nlohmann::json result = core::run_ffd_benchmark(o);
  if (options.json)
    out << result.dump() << "\n";
  else
    core::print_ffd_benchmark(result, out);
  return 0;
}

}  // namespace trispline::editor
