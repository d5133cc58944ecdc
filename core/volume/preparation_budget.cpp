#include "core/volume/preparation_budget.h"

#include <algorithm>
#include <limits>

#include "core/volume/singletons.h"

namespace trispline::core {

namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r = 0;
  return __builtin_mul_overflow(a, b, &r) ? kSaturated : r;
}

std::uint64_t add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r = 0;
  return __builtin_add_overflow(a, b, &r) ? kSaturated : r;
}

std::string mib(std::uint64_t bytes) {
  if (bytes == kSaturated) return "more than 16 EiB";
  return std::to_string((bytes + (1ull << 20) - 1) >> 20) + " MiB";
}

}  // namespace

std::uint64_t preparation_bytes(const std::array<std::int64_t, 3>& dims, int order) {
  std::uint64_t voxels = 1, macros = 1, longest = 0;
  for (const std::int64_t d : dims) {
    const std::uint64_t n = d < 1 ? 1 : static_cast<std::uint64_t>(d);
    voxels = mul(voxels, n);
    // Cells per axis: n − 1 for even orders, n for odd ones; macro-cells of 8 cells (rounded up).
    const std::uint64_t cells = order % 2 == 0 && n > 1 ? n - 1 : n;
    macros = mul(macros, (cells + SingletonTable::kMacro - 1) / SingletonTable::kMacro);
    longest = std::max(longest, n);
  }
  const std::uint64_t bins = static_cast<std::uint64_t>(kSingletonTableRows) * kSingletonTableColumns;
  const std::uint64_t fixed = bins * 16 + 4 +                // bin offsets, counts, fill cursors, cone angles
                              8 * bins * 8 +                 // per-thread counts and cones while filing (8 threads)
                              kSingletonColumnProbes * 12 +  // the column radius' probe directions
                              2 * 8 * longest +              // the prefilter's two line buffers (double)
                              (1ull << 16);                  // histogram, column axes, headers
  std::uint64_t total = mul(voxels, 4 + kPreparationBytesPerVoxel);
  total = add(total, mul(macros, 8));
  return add(total, fixed);
}

void check_preparation_budget(const std::string& source, const std::array<std::int64_t, 3>& dims, int order,
                              std::uint64_t budget_bytes) {
  const std::uint64_t need = preparation_bytes(dims, order);
  if (need <= budget_bytes) return;
  throw PreparationBudgetError(
      source + ": a volume of " + std::to_string(dims[0]) + "×" + std::to_string(dims[1]) + "×" +
      std::to_string(dims[2]) + " samples needs " + mib(need) + " to prepare at order " + std::to_string(order) + " (" +
      std::to_string(4 + kPreparationBytesPerVoxel) +
      " bytes per sample: control point, singleton, lookup-table entry and its sort key), over the memory "
      "budget of " +
      mib(budget_bytes) + "; crop or resample it first");
}

}  // namespace trispline::core
