// cpu_fast instruction-set selection: CPU feature checks (__builtin_cpu_supports), TRISPLINE_SIMD, overrides.
#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "core/ffd/ffd_fast.h"
#include "core/ffd/ffd_fast_kernel.h"

namespace trispline::core {
namespace ffd_fast_detail {
namespace {

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
bool cpu_has_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2");
}
bool cpu_has_avx512() {
  return cpu_has_avx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd");
}
#else
bool cpu_has_avx2() { return false; }
bool cpu_has_avx512() { return false; }
#endif

// Usable tables, lowest first.
std::vector<const KernelTable*> usable() {
  std::vector<const KernelTable*> v{kernels_baseline()};
  if (kernels_avx2() && cpu_has_avx2()) v.push_back(kernels_avx2());
  if (kernels_avx512() && cpu_has_avx512()) v.push_back(kernels_avx512());
  return v;
}

int rank(std::string_view name) {
  if (name == "sse" || name == "generic" || name == "baseline") return 0;
  if (name == "avx2") return 1;
  if (name == "avx512") return 2;
  if (name == "auto" || name.empty()) return 3;
  return -1;
}

const KernelTable* choose(std::string_view name) {
  const int want = rank(name);
  if (want < 0)
    throw std::invalid_argument("cpu_fast: unknown instruction set '" + std::string(name) +
                                "' (expected auto, sse, avx2 or avx512)");
  const KernelTable* best = kernels_baseline();
  for (const KernelTable* t : usable())
    if (rank(t->isa) <= want) best = t;
  return best;
}

std::atomic<const KernelTable*> g_active{nullptr};

}  // namespace

const KernelTable* active_kernels() {
  const KernelTable* t = g_active.load(std::memory_order_acquire);
  if (!t) {
    const char* env = std::getenv("TRISPLINE_SIMD");
    try {
      t = choose(env ? env : "auto");
    } catch (const std::invalid_argument&) {
      t = choose("auto");  // an unknown TRISPLINE_SIMD value is ignored
    }
    g_active.store(t, std::memory_order_release);
  }
  return t;
}

}  // namespace ffd_fast_detail

const char* ffd_fast_isa() { return ffd_fast_detail::active_kernels()->isa; }

const char* ffd_fast_select_isa(std::string_view name) {
  const ffd_fast_detail::KernelTable* t = ffd_fast_detail::choose(name);
  ffd_fast_detail::g_active.store(t, std::memory_order_release);
  return t->isa;
}

std::vector<std::string> ffd_fast_available_isas() {
  std::vector<std::string> names;
  for (const auto* t : ffd_fast_detail::usable()) names.emplace_back(t->isa);
  return names;
}

}  // namespace trispline::core
