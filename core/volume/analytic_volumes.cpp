#include "core/volume/analytic_volumes.h"

#include <cmath>
#include <stdexcept>

#include "core/base/enum_names.h"

namespace trispline::core {

double analytic_field(AnalyticVolume kind, const glm::dvec3& p, const AnalyticShape& s) {
  switch (kind) {
    case AnalyticVolume::sphere:
      return s.sphere_radius - glm::length(p);
    case AnalyticVolume::torus: {
      const double q = std::sqrt(p.x * p.x + p.y * p.y) - s.torus_major;
      return s.torus_minor - std::sqrt(q * q + p.z * p.z);
    }
    case AnalyticVolume::sines: {
      const double w = 2.0 * 3.14159265358979323846 / s.sines_period;
      return std::sin(w * p.x) * std::sin(w * p.y) * std::sin(w * p.z);
    }
  }
  return 0.0;
}

ScalarVolume make_analytic_volume(AnalyticVolume kind, int n, const AnalyticShape& shape) {
  if (n < 4 || n > 1024)
    throw std::invalid_argument("analytic volume size must be 4…1024 samples, got " + std::to_string(n));
  ScalarVolume v;
  v.dims = {n, n + n / 4, n - n / 5};
  v.values.resize(v.voxel_count());
  glm::dmat4 m(1.0);
  for (int a = 0; a < 3; ++a) {
    m[a][a] = 2.0 * shape.extent / (v.dims[a] - 1);
    m[3][a] = -shape.extent;
  }
  v.index_to_world = m;
  v.source = std::string("analytic:") + analytic_volume_name(kind);
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i)
        v.values[v.index(i, j, k)] = static_cast<float>(analytic_field(kind, v.world(glm::dvec3(i, j, k)), shape));
  return v;
}

const char* analytic_volume_name(AnalyticVolume kind) { return enum_name(kind, {"sphere", "torus", "sines"}); }

bool parse_analytic_volume(const std::string& name, AnalyticVolume& kind) {
  for (AnalyticVolume k : {AnalyticVolume::sphere, AnalyticVolume::torus, AnalyticVolume::sines})
    if (name == analytic_volume_name(k)) return kind = k, true;
  return false;
}

}  // namespace trispline::core
