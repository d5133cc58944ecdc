#include "editor/bench_ffd.h"

#include <epoxy/gl.h>

#include <iostream>
#include <memory>

#include "core/deform/ffd_bench.h"
#include "gpu/ffd_gl.h"
#include "gpu/gl_context.h"

namespace trispline::editor {

int run_bench_ffd(const BenchFfdOptions& options, std::ostream& out, std::ostream& err) {
  core::FfdBenchOptions o;
  if (!options.mesh_path.empty()) o.mesh_path = options.mesh_path;
  o.subdivision_level = options.subdivision >= 0 ? options.subdivision : (options.mesh_path.empty() ? 2 : 0);
  o.runs = options.runs;
  o.progress = [&err](const std::string& line) { err << "bench ffd: " << line << "\n" << std::flush; };

  std::unique_ptr<gpu::HeadlessContext> context;
  if (options.gpu) {
    try {
      context = std::make_unique<gpu::HeadlessContext>();
      o.renderer = context->renderer();
      // One program cache for all evaluators: "end_to_end" makes a fresh evaluator per run, and llvmpipe would
      // otherwise JIT-compile the program again each time (about a second), which is not what we measure.
      auto programs = std::make_shared<gpu::FfdProgramCache>();
      o.gpu_shaders = gpu::is_software_renderer() ? "generic orders (software renderer: one program for all orders)"
                                                  : "order-specialised (ORDER_U/V/W defines, unrolled loops)";
      for (core::FfdBackend b : {core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex})
        o.gpu_backends.push_back(
            {b, [b, programs] { return gpu::make_gl_ffd_evaluator(b, programs); }, [] { glFinish(); }});
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
