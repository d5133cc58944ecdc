// trispline::core::detail::Scratch — a small-buffer array of doubles for per-evaluation temporaries
// (basis tables, Cox–de Boor triangles), so hot evaluation paths do not allocate for usual orders (≤ 8 per axis).
// Internal to core/spline.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace trispline::core::detail {

template <std::size_t Inline = 96>
class Scratch {
 public:
  explicit Scratch(std::size_t n) : data_(n <= Inline ? inline_.data() : (heap_.resize(n), heap_.data())) {}
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  double* data() { return data_; }
  double& operator[](std::size_t i) { return data_[i]; }

 private:
  std::array<double, Inline> inline_;
  std::vector<double> heap_;
  double* data_;
};

}  // namespace trispline::core::detail
