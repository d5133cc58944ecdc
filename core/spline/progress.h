// trispline::core::ProgressSink and OperationCancelled — the progress and cancel contract of every long core
// operation (a volume's singleton table, a DDM layer's evaluation, a command prepared on a worker thread). Kept in the
// lowest module so any module may take one; it holds no GUI: the editor passes a sink whose cancel flag its Cancel
// button sets.
#pragma once

#include <atomic>
#include <functional>
#include <stdexcept>

namespace trispline::core {

// Thrown by long operations when their cancel flag is set; nothing they were building is kept.
struct OperationCancelled : std::runtime_error {
  OperationCancelled() : std::runtime_error("cancelled") {}
};

// Progress of a long operation: report(fraction in [0,1]) is called from the calling thread now and then (may be
// empty); when *cancel becomes true the operation throws OperationCancelled (cancel may be null).
struct ProgressSink {
  std::function<void(double)> report;
  const std::atomic<bool>* cancel = nullptr;
  void check(double fraction) const {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw OperationCancelled();
    if (report) report(fraction);
  }
};

// Reports `sink` (may be null) at `fraction`; throws OperationCancelled when its cancel flag is set.
inline void check_progress(const ProgressSink* sink, double fraction) {
  if (sink) sink->check(fraction);
}

// The part [lo, hi] of a parent's progress given to a sub-step: the sub-step reports in [0, 1]. Holds `parent` by
// pointer (may be null: then it reports nothing and never cancels); must not outlive it.
inline ProgressSink progress_range(const ProgressSink* parent, double lo, double hi) {
  ProgressSink s;
  if (!parent) return s;
  s.cancel = parent->cancel;
  if (parent->report) s.report = [parent, lo, hi](double f) { parent->report(lo + (hi - lo) * f); };
  return s;
}

}  // namespace trispline::core
