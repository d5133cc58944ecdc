// trispline::core FFD evaluator contract — one interface, several backends (seed ch. 4).
//
// What an FFD evaluation takes:
//   * per-vertex inputs, bound once (the parameters of a mesh do not change while its lattice moves, seed §4.2):
//       params        #V × 3  parametric coordinates (u,v,w), parameter domain [0,1]³
//       rest_normals  #V × 3  unit normals in world rest space, or empty for positions only
//   * the deformation, set whenever control points move: the control lattice F (control points in world units,
//     knot vectors, order per axis — order = degree + 1) and the embedding E (its linear part A enters the normals);
//   * an optional parameter offset added to every vertex's (u,v,w) at evaluation (seed §4.5 animation offset).
// What it returns: positions #V × 3 (world units) F(uvw + offset) and normals #V × 3 (unit)
//   n' ∝ cof(J_F · A) · n   (exact, through the Jacobian's cofactor matrix, seed §4.3 — no finite differences);
//   where cof(J_F·A)·n vanishes the rest normal is returned.
// Parameters outside a knot vector's domain are clamped to it; on a periodic axis (KnotVector::is_periodic) they
// wrap instead (t − ⌊t⌋), so an offset of one full period returns every vertex to its start.
//
// Backends (identical signatures, as OpenSubdiv's Cpu*/GL* evaluators):
//   cpu_ref       double precision reference (core/ffd/ffd.h), any order, deterministic for any thread count
//   cpu_fast      float, oneTBB, vectorised across vertices (core/ffd/ffd_fast.h); orders 2..4
//   glsl_compute  GLSL compute shader writing into GL buffers the renderer draws (gpu/eval/ffd_gl.h); orders 2..4
//   glsl_vertex   GLSL vertex-shader path (seed §4.2.1 single phase), evaluated while drawing; results for read-back
//                 come through transform feedback of the same shader (gpu/eval/ffd_gl.h); orders 2..4
// Accuracy contract (tests): every backend within 1e-5 × lattice bounding-box diagonal of cpu_ref in position,
// normals within 1e-4 rad.
// Threads: CPU backends run on the calling thread's oneTBB arena (limit with tbb::global_control / task_arena).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "core/ffd/ffd.h"

namespace trispline::core {

enum class FfdBackend { cpu_ref, cpu_fast, glsl_compute, glsl_vertex };

// "cpu_ref", "cpu_fast", "glsl_compute", "glsl_vertex" (the names used by `bench ffd --json` and the settings).
const char* to_string(FfdBackend backend);
// Inverse of to_string; nullopt for anything else.
std::optional<FfdBackend> parse_ffd_backend(std::string_view name);
// True for glsl_compute and glsl_vertex (they need a current GL 4.3 context).
inline bool is_gpu_backend(FfdBackend b) { return b == FfdBackend::glsl_compute || b == FfdBackend::glsl_vertex; }

class FfdEvaluator {
 public:
  virtual ~FfdEvaluator() = default;
  virtual FfdBackend backend() const = 0;

  // Binds the per-vertex inputs (see the header comment). Per-mesh precomputation happens here (e.g. sorting
  // vertices by lattice cell, GPU uploads). Throws std::invalid_argument if rest_normals is neither empty nor
  // #params long, or an input is non-finite.
  virtual void bind_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals) = 0;

  // Sets the deformation. Cheap enough to call every time control points move (O(#controls), not O(#V)).
  // Throws std::invalid_argument if an order is outside what the backend supports (cpu_ref: any; others: 2..4).
  virtual void set_lattice(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding) = 0;

  // Evaluates every bound vertex at params + param_offset (parameter units). Needs bind_vertices and set_lattice
  // first (throws std::logic_error otherwise). GPU backends return after issuing the work, without waiting.
  virtual void evaluate(const glm::dvec3& param_offset = glm::dvec3(0.0)) = 0;

  // Copies the latest results to the host, waiting for the GPU if needed: positions #V × 3 world units, normals
  // #V × 3 unit (cleared when bound without normals). Throws std::logic_error before the first evaluate().
  virtual void read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) = 0;
  // The same in single precision, for display (the renderer uploads floats): #V × 3 each. The default converts
  // read_results(); cpu_fast overrides it to skip the float → double → float round trip (half the cost of a live
  // preview on a 1 M-vertex object).
  virtual void read_results_float(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);
  // The same into caller memory: `positions` #V × 3 doubles (world units), `normals` #V × 3 (unit; null, or ignored
  // when bound without normals). No allocation: a caller that keeps its buffers (Python's out= arrays) pays only the
  // copy. The default goes through read_results(); cpu_fast writes straight from its float results.
  virtual void read_results_into(double* positions, double* normals);
  // evaluate(param_offset) with its results in caller memory, as read_results_into() would copy them, bit for bit
  // (cpu_fast writes them from its kernels, without a float pass, and its read_results*() then throw
  // std::logic_error until the next evaluate(): its own result buffers are not this evaluation's).
  virtual void evaluate_into(const glm::dvec3& param_offset, double* positions, double* normals);

  virtual std::size_t vertex_count() const = 0;
  virtual bool has_normals() const = 0;
};

// CPU backends: backend must be cpu_ref or cpu_fast (throws std::invalid_argument otherwise; GPU backends are made by
// gpu::make_gl_ffd_evaluator, which needs a GL context).
std::unique_ptr<FfdEvaluator> make_cpu_ffd_evaluator(FfdBackend backend);

}  // namespace trispline::core
