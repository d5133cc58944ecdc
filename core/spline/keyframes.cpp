// Keyframe evaluation. See keyframes.h.
#include "core/spline/keyframes.h"

#include <algorithm>
#include <stdexcept>

namespace trispline::core {

glm::dvec3 evaluate_offset_keys(const std::vector<OffsetKey>& keys, double time_s) {
  if (keys.empty()) throw std::invalid_argument("evaluate_offset_keys: no keys");
  if (time_s <= keys.front().time_s) return keys.front().offset;
  if (time_s >= keys.back().time_s) return keys.back().offset;
  // First key later than time_s; keys are sorted and distinct, so a and b bracket time_s with a.time < b.time.
  const auto b =
      std::upper_bound(keys.begin(), keys.end(), time_s, [](double t, const OffsetKey& k) { return t < k.time_s; });
  const OffsetKey& k1 = *b;
  const OffsetKey& k0 = *(b - 1);
  const double s = (time_s - k0.time_s) / (k1.time_s - k0.time_s);
  switch (k0.interpolation) {
    case KeyInterpolation::constant:
      return k0.offset;
    case KeyInterpolation::smooth: {
      const double e = s * s * (3.0 - 2.0 * s);  // cubic Hermite with zero tangents at both keys
      return k0.offset + (k1.offset - k0.offset) * e;
    }
    case KeyInterpolation::linear:
      break;
  }
  return k0.offset + (k1.offset - k0.offset) * s;
}

}  // namespace trispline::core
