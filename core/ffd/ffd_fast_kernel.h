// Internal to core/ffd: the plain data the cpu_fast evaluator (ffd_fast.cpp, baseline ISA, oneTBB)
// hands to the per-ISA block kernels (ffd_fast_kernel_impl.h compiled once per ISA). Only PODs and raw pointers
// cross this boundary, so no inline function compiled for a wider ISA can leak into baseline code through the
// linker's choice of COMDAT copies.
//
// Vertices are bound in blocks of kLanes (16) that share one lattice cell (product of one non-empty span per axis);
// block b's lane l is element b·kLanes + l of every per-lane array; tails are padded by repeating the cell's last
// vertex (the duplicate writes store identical values).
#pragma once

#include <cstddef>
#include <cstdint>

namespace trispline::core {
struct FfdPackedLattice;
struct FfdPackedAxis;
}  // namespace trispline::core

namespace trispline::core::ffd_fast_detail {

constexpr int kLanes = 16;

// One axis of the lattice for locating spans on the fly (ffd_packed.h rules: wrap/clamp, O(1) or binary search).
struct AxisTable {
  int order = 0, span_count = 0;
  bool periodic = false, uniform = false;
  float domain_min = 0, domain_max = 1, inv_uniform_len = 1;
  const float* span_begin = nullptr;    // #S + 1
  const float* inv_span_len = nullptr;  // #S
};

// View of a packed axis (pointers into `a`, which must outlive the table). Defined in ffd_fast_gather.cpp.
AxisTable axis_table(const FfdPackedAxis& a);

// Per-cell power-basis tables. Cell id = su + S_u·(sv + S_v·sw) (span slots per axis).
struct CellTables {
  // #cells × stride floats; coefficient of x_u^a x_v^b x_w^c of component d (x,y,z) at ((a·OV + b)·OW + c)·3 + d,
  // positions relative to the lattice's bounding-box centre (world units).
  const float* coef = nullptr;
  int stride = 0;
  // #cells × 9, row-major 3×3: cof(D_cell)·cof(A) scaled to O(1/|J|²), D_cell = diag(1/span length) per axis, so
  // that cof(J_x)·(N·n) ∝ cof(J_F·A)·n with J_x the Jacobian in the cell's local coordinates.
  const float* normal_matrix = nullptr;
  AxisTable axis[3];
};

struct BlockArrays {
  const float *xu = nullptr, *xv = nullptr, *xw = nullptr;  // local coordinates in the block's rest cell, [0,1]
  const float *pu = nullptr, *pv = nullptr, *pw = nullptr;  // parameters (offset path)
  const float *nx = nullptr, *ny = nullptr, *nz = nullptr;  // rest normals (null: positions only)
  const std::int32_t* index = nullptr;                      // original vertex index per lane
  const std::int32_t* cell = nullptr;                       // rest cell per block
};

struct Outputs {
  float* positions = nullptr;  // #V × 3 (AoS), relative to the lattice centre
  float* normals = nullptr;    // #V × 3 (AoS), unit; null for positions only
  // Set: the block kernels write here instead, in double (positions64 = centre + the float result, world units;
  // normals64 = the float normal widened), the arithmetic of FfdFastEvaluator::read_results_into, so a caller that
  // keeps float64 arrays skips the float pass. The gather kernel does not take them.
  double* positions64 = nullptr;  // #V × 3 (AoS), world units
  double* normals64 = nullptr;    // #V × 3 (AoS), unit; null for positions only
  double centre[3] = {0, 0, 0};   // the lattice centre, world units
};

// Evaluates blocks [block_begin, block_end). offset: null for the rest path (cells and local coordinates from
// binding), else the parameter offset (u,v,w) — spans are then located per lane.
using BlockKernel = void (*)(const CellTables& tables, const BlockArrays& blocks, const Outputs& out,
                             std::size_t block_begin, std::size_t block_end, const float* offset);

// Kernels of one ISA, indexed [ou−2][ov−2][ow−2][normals].
struct KernelTable {
  const char* isa;  // "sse", "avx2", "avx512" or "generic"
  BlockKernel kernel[3][3][3][2];
};

// Per-ISA tables (null when the ISA is not compiled in, e.g. not x86-64). active_kernels(): the one in use
// (ffd_fast_dispatch.cpp).
const KernelTable* kernels_baseline();
const KernelTable* kernels_avx2();
const KernelTable* kernels_avx512();
const KernelTable* active_kernels();

// Per-vertex gather kernel (ffd_fast_gather.cpp, baseline ISA) for lattices too big for cell tables: vertices
// [begin, end) of params (#V × 3 AoS float) at params + offset, rest normals (#V × 3 AoS, null for positions only);
// outputs as Outputs (relative to the lattice centre).
struct GatherInput {
  const FfdPackedLattice* lattice = nullptr;
  const float* params = nullptr;
  const float* normals = nullptr;
  float offset[3] = {0, 0, 0};
};
void gather_evaluate(const GatherInput& in, const Outputs& out, std::size_t begin, std::size_t end);

}  // namespace trispline::core::ffd_fast_detail
