// trispline::core the memory budget of preparing a volume (seed ch. 7): what reading a volume, making its spline D and
// its singleton table holds at worst, computed from the dimensions and the order before anything is allocated.
//
//   kPreparedVolumeBudget      bytes a volume may take while it is prepared (samples, spline, table, file buffers)
//   kPreparationBytesPerVoxel  bytes per sample that preparation adds to the loader's float samples
//   preparation_bytes          worst-case bytes for given dimensions and order
//   check_preparation_budget   throws PreparationBudgetError (names the source and the figures) when over budget
//
// The peak is reached while the lookup table's bins are sorted: per sample, the spline's control point (float, 4), a
// Singleton per cell (24; a spline has at most as many cells as samples), the cell's bin entry (4) and, at worst, its
// 8-byte sort key (when one bin holds every cell) — 40 bytes. The loader's float samples (4) are freed once the
// spline holds its control points, and the loader's own file buffers before that, so the budget charges 4 (what the
// loader counts) + kPreparationBytesPerVoxel (36) = 40 bytes per sample, plus the fixed arrays. Reading a cached
// table peaks the same (its singletons, then the same filing). Measured on the Cranium CT (7.08 M samples): 35.1
// bytes per sample of peak resident memory above an empty replay (docs/decisions.md, "The preparation budget").
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace trispline::core {

// Bytes a volume may take while it is prepared: 6 GiB, about 160 M samples (a 512×512×600 CT) at 40 bytes each.
inline constexpr std::uint64_t kPreparedVolumeBudget = 6ull << 30;

// Bytes per sample that preparation holds at its peak beyond the 4 the loader counts for the float samples (40 in all:
// control point 4, Singleton 24, bin entry 4, sort key 8). volume.load (through prepare_volume) passes it to the
// loader as VolumeLoadOptions::extra_bytes_per_voxel, so a file whose header dimensions are over budget is refused
// before a byte is inflated.
inline constexpr std::uint64_t kPreparationBytesPerVoxel = 36;

// Refused preparation: the message names the source, the dimensions, the bytes needed and the budget.
class PreparationBudgetError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Worst-case bytes of preparing a volume of dims[0]×dims[1]×dims[2] samples (each ≥ 1) at `order` (2…4):
// (4 + kPreparationBytesPerVoxel) per sample + the 8³ macro-cells' ranges (8 bytes each) + the lookup table's fixed
// arrays (bins, per-thread partials for 8 threads, column probes) + the interpolation prefilter's line buffers.
// Saturates at UINT64_MAX instead of overflowing, so absurd header dimensions compare as over any budget.
std::uint64_t preparation_bytes(const std::array<std::int64_t, 3>& dims, int order);

// Throws PreparationBudgetError when preparation_bytes(dims, order) > budget_bytes: "<source>: a volume of
// X×Y×Z samples needs N MiB to prepare at order K (40 bytes per sample: ...), over the memory budget of B MiB; crop
// or resample it first".
void check_preparation_budget(const std::string& source, const std::array<std::int64_t, 3>& dims, int order,
                              std::uint64_t budget_bytes = kPreparedVolumeBudget);

}  // namespace trispline::core
