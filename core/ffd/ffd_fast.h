// trispline::core cpu_fast — the single-precision, vectorised CPU backend of the FFD evaluator contract
// (ffd_evaluator.h; made by make_cpu_ffd_evaluator(FfdBackend::cpu_fast)). Orders 2..4 per axis (all 27
// combinations), clamped, floating, non-uniform and periodic knot vectors.
//
// How it is fast (figures in docs/performance.md):
//   * set_lattice (O(#cells · order³)): per lattice cell (one non-empty knot span per axis) the B-spline is one
//     tri-variate polynomial; its power-basis coefficients c_abc (xyz) in the cell's local coordinates
//     x_u, x_v, x_w ∈ [0,1] are folded once, in double, from SpanBasis tables (P&T §2.5) and the control points;
//   * binding (first evaluate after bind_vertices or after the knot vectors change, O(#V)): each vertex's cell and
//     local coordinates are found in double; vertices are sorted by cell (stable) into blocks of 16 of one cell,
//     tails padded; structure-of-arrays float;
//   * evaluate: per block, Horner in w, v, u on the cell's coefficients (broadcast) with 16 vertices in vector
//     lanes; normals by Horner with derivatives and n' ∝ cof(J_x)·(cof(D)·cof(A)·n) (D = 1 / span lengths, A the
//     embedding's linear part; = cof(J_F·A)·n, seed §4.3); results written in the caller's vertex order;
//   * the kernels are compiled for several instruction sets (x86-64 baseline SSE2, x86-64-v3 AVX2+FMA, x86-64-v4
//     AVX-512) and chosen at run time (ffd_fast_isa); the rest of the build stays portable;
//   * param_offset ≠ 0 (animation): spans are located per vertex at params + offset; a block is evaluated once per
//     distinct cell among its lanes (at most a few: the block's vertices shared a cell before the shift);
//   * lattices whose cell tables would exceed kMaxCellTableFloats (32 MiB) use a per-vertex gather kernel instead
//     (basis per axis from the FfdPackedLattice tables, control points gathered): slower, any lattice size.
// Positions are computed relative to the lattice's bounding-box centre and the centre is added in double by
// read_results, so float rounding is relative to the lattice size, not to its distance from the origin.
// Deterministic: every vertex runs a fixed operation sequence independent of its block neighbours and of the
// partition, so results are bit-identical for any thread count on one machine and ISA (not across ISAs: the AVX
// kernels use FMA).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/ffd/ffd_evaluator.h"

namespace trispline::core {

class FfdFastEvaluator final : public FfdEvaluator {
 public:
  // Upper bound on the per-cell coefficient tables, in floats (#cells · (3·order_u·order_v·order_w + 9)).
  static constexpr std::size_t kMaxCellTableFloats = std::size_t(1) << 23;

  FfdFastEvaluator();
  ~FfdFastEvaluator() override;

  FfdBackend backend() const override { return FfdBackend::cpu_fast; }
  // See FfdEvaluator. Also throws std::invalid_argument for more than 2^31 − 1 vertices.
  void bind_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals) override;
  // See FfdEvaluator; throws std::invalid_argument if an order is outside 2..4. Rebuilds the cell tables
  // (O(#cells·order³)); re-bins the vertices (O(#V)) only when a knot vector changed.
  void set_lattice(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding) override;
  // See FfdEvaluator. The offset is wrapped (in double) to [0,1) on periodic axes first, so a whole-period offset
  // reproduces the rest evaluation bit for bit.
  void evaluate(const glm::dvec3& param_offset = glm::dvec3(0.0)) override;
  void read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) override;
  void read_results_float(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) override;
  void read_results_into(double* positions, double* normals) override;
  // Block kernels write the doubles directly (no float pass); gather mode: evaluate() + read_results_into().
  void evaluate_into(const glm::dvec3& param_offset, double* positions, double* normals) override;
  std::size_t vertex_count() const override;
  bool has_normals() const override;

  // False when the lattice's cell tables would exceed kMaxCellTableFloats and the gather kernel runs.
  bool uses_cell_tables() const;
  // Blocks of 16 same-cell vertices of the current binning (0 before the first evaluate or in gather mode).
  std::size_t block_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The instruction set the cpu_fast kernels use: "sse" (x86-64 baseline), "avx2" (x86-64-v3: AVX2 + FMA),
// "avx512" (x86-64-v4) or "generic" (other architectures). Chosen at first use: the best the CPU supports, or the
// environment variable TRISPLINE_SIMD=sse|avx2|avx512 (capped at what the CPU supports).
const char* ffd_fast_isa();
// Switches the instruction set for later evaluations ("auto" = best available); a request above what the CPU or
// build supports falls back to the best lower one. Returns the ISA now in use. Throws std::invalid_argument for
// an unknown name. Call it between evaluations, not during one.
const char* ffd_fast_select_isa(std::string_view name);
// Instruction sets usable on this machine and build, lowest first (e.g. {"sse", "avx2", "avx512"}).
std::vector<std::string> ffd_fast_available_isas();

namespace detail {
// Checks per-vertex FFD inputs (shared by the CPU evaluators): rest_normals empty or #params long, all finite.
// Throws std::invalid_argument naming `who`.
void check_ffd_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals,
                        const char* who);
}  // namespace detail

}  // namespace trispline::core
