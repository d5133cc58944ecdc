// trispline::core::ScalarVolume — a CT/MRI volume as read from its file: a regular grid of scalar samples and the
// affine map from voxel indices to world coordinates (millimetres in the file's own patient/scanner space).
//
// Samples are stored as float, x fastest: values[i + nx·(j + ny·k)] is voxel (i, j, k). Index space is continuous:
// voxel (i, j, k) sits at the index-space point (i, j, k), so the grid spans [0, nx−1] × [0, ny−1] × [0, nz−1].
// World = index_to_world · (i, j, k, 1): NIfTI's sform (else qform) affine, DICOM's Image Position/Orientation and
// Pixel Spacing, an .inv3 project's spacing with the origin at voxel (0,0,0).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace trispline::core {

struct ScalarVolume {
  std::array<int, 3> dims{0, 0, 0};  // nx, ny, nz (samples per axis, each ≥ 2 for a usable volume)
  std::vector<float> values;         // nx·ny·nz samples, x fastest, in `units`
  glm::dmat4 index_to_world{1.0};  // voxel index (i, j, k, 1) → world position, millimetres (affine: last row 0 0 0 1)
  std::string units;               // value units: "HU" for CT, "" when the file says nothing
  std::string modality;            // "CT", "MR", ... or "" (DICOM 0008,0060; NIfTI and .inv3: guessed or "")
  std::string source;              // the file or folder it was read from
  // The patient axes of the world frame: "RAS" (NIfTI: +x right, +y anterior, +z superior), "LPS" (DICOM), or ""
  // when the file gives none (.inv3, analytic volumes).
  std::string frame;

  std::size_t voxel_count() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims[0]) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * k);
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  // World position of an index-space point (millimetres).
  glm::dvec3 world(const glm::dvec3& ijk) const { return glm::dvec3(index_to_world * glm::dvec4(ijk, 1.0)); }
};

// What is wrong with `v` as a volume (dims < 2 on an axis, values.size() ≠ product of dims, a non-finite sample, a
// singular or non-finite index_to_world, a last row other than 0 0 0 1), or "" when it is usable.
std::string scalar_volume_error(const ScalarVolume& v);

}  // namespace trispline::core
