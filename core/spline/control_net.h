// Helpers shared by the curve, surface and trivariate classes (internal to core/spline):
//   - finiteness checks of control points with a message naming the offending index;
//   - the strided "axis view" of a u-fastest control array: element (a, i, b) of an axis with n controls lies at
//     a + inner·(i + n·b), a ∈ [0,inner) (faster axes), b ∈ [0,outer) (slower axes).
#pragma once

#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace trispline::core::detail {

inline bool is_finite(double x) { return std::isfinite(x); }
template <int L>
bool is_finite(const glm::vec<L, double>& v) {
  for (int c = 0; c < L; ++c)
    if (!std::isfinite(v[c])) return false;
  return true;
}

// Throws std::invalid_argument("<who>: ...") if cps.size() != expected or any control point is not finite.
template <class T>
void check_control_points(const std::vector<T>& cps, std::size_t expected, const char* who) {
  if (cps.size() != expected)
    throw std::invalid_argument(std::string(who) + ": wrong control point count: got " + std::to_string(cps.size()) +
                                ", the knot vectors need " + std::to_string(expected));
  for (std::size_t i = 0; i < cps.size(); ++i)
    if (!is_finite(cps[i]))
      throw std::invalid_argument(std::string(who) + ": control point " + std::to_string(i) +
                                  " is not finite (NaN or Inf)");
}

// Throws std::invalid_argument if t is NaN (evaluation clamps finite out-of-domain parameters instead).
inline void check_parameter(double t, const char* who) {
  if (std::isnan(t)) throw std::invalid_argument(std::string(who) + ": parameter is NaN");
}

}  // namespace trispline::core::detail
