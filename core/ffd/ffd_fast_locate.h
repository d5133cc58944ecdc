// Internal to core/ffd: span location on one axis for the gather kernel, exactly as ffd_packed.h specifies
// (wrap on a periodic axis, else clamp; O(1) lookup with a one-span correction for uniform spans, else binary
// search; local coordinate (t − span_begin[s])·inv_span_len[s]). The block kernels have a vector version
// (locate_vec in ffd_fast_kernel_impl.h). In an anonymous namespace so that a file compiled for a wider ISA that
// includes it gets its own copy.
#pragma once

#include "core/ffd/ffd_fast_kernel.h"

namespace trispline::core::ffd_fast_detail {
namespace {

[[gnu::always_inline]] inline int locate_span(const AxisTable& a, float t, float* x) {
  if (a.periodic) t -= __builtin_floorf(t);
  t = t >= a.domain_min ? t : a.domain_min;  // also maps NaN to domain_min
  t = t <= a.domain_max ? t : a.domain_max;
  const int S = a.span_count;
  int s;
  if (a.uniform) {
    s = static_cast<int>((t - a.domain_min) * a.inv_uniform_len);  // argument ≥ 0: truncation = floor
    s = s < S - 1 ? s : S - 1;
    s -= (t < a.span_begin[s]) ? 1 : 0;
    s += (s + 1 < S && t >= a.span_begin[s + 1]) ? 1 : 0;
  } else {
    int lo = 0, hi = S - 1;  // last s with span_begin[s] ≤ t
    while (lo < hi) {
      const int mid = (lo + hi + 1) / 2;
      if (a.span_begin[mid] <= t)
        lo = mid;
      else
        hi = mid - 1;
    }
    s = lo;
  }
  *x = (t - a.span_begin[s]) * a.inv_span_len[s];
  return s;
}

}  // namespace
}  // namespace trispline::core::ffd_fast_detail
