#include "core/volume/scalar_volume.h"

#include <cmath>

namespace trispline::core {

std::string scalar_volume_error(const ScalarVolume& v) {
  for (int a = 0; a < 3; ++a)
    if (v.dims[a] < 2)
      return "the volume has " + std::to_string(v.dims[a]) + " sample(s) along axis " + "xyz"[a] +
             " (at least 2 are needed)";
  if (v.values.size() != v.voxel_count())
    return "the volume holds " + std::to_string(v.values.size()) + " samples for " + std::to_string(v.dims[0]) + "×" +
           std::to_string(v.dims[1]) + "×" + std::to_string(v.dims[2]) + " voxels";
  for (std::size_t i = 0; i < v.values.size(); ++i)
    if (!std::isfinite(v.values[i])) return "sample " + std::to_string(i) + " is not a finite number";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(v.index_to_world[c][r])) return "the voxel-to-world matrix is not finite";
  if (v.index_to_world[0][3] != 0.0 || v.index_to_world[1][3] != 0.0 || v.index_to_world[2][3] != 0.0 ||
      v.index_to_world[3][3] != 1.0)
    return "the voxel-to-world matrix is not affine";
  const glm::dmat3 a(v.index_to_world);
  double scale = 0.0;
  for (int c = 0; c < 3; ++c) scale = std::max(scale, glm::length(a[c]));
  const double det = glm::determinant(a);
  if (!(scale > 0.0) || !(std::abs(det) > 1e-12 * scale * scale * scale))
    return "the voxel-to-world matrix is singular (a zero or repeated voxel axis)";
  return {};
}

}  // namespace trispline::core
