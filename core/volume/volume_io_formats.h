// Private to load_volume (core/volume/volume_io.cpp): one reader per format and the checks they share.
//
//   load_nifti  volume_io_nifti.cpp   .nii / .nii.gz through niftilib
//   load_dicom  volume_io_dicom.cpp   a DICOM series (folder or one .dcm file) through GDCM, each file walked
//                                     first by walk_dicom_file (volume_io_dicom_walk.h)
//   load_inv3   volume_io_inv3.cpp    an InVesalius .inv3 project through libarchive + tinyxml2
//
// Each returns a volume with dims, values, index_to_world, units and modality set, or throws VolumeLoadError via
// fail(); load_volume sets `source` and runs scalar_volume_error on the result.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <vector>

#include "core/volume/scalar_volume.h"
#include "core/volume/volume_io.h"

namespace trispline::core::volume_io {

// Samples converted per block when a reader streams (NIfTI, .inv3): the file buffer a load holds besides the floats.
inline constexpr std::size_t kStreamBlockBytes = std::size_t{1} << 20;

// A computed sample as float; beyond float's range it becomes ±inf (refused later as non-finite) rather than an
// undefined conversion.
inline float to_float(double x) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (x > kMax) return std::numeric_limits<float>::infinity();
  if (x < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(x);
}

// 'path' in quotes, for messages.
std::string quoted(const std::filesystem::path& path);

// Throws VolumeLoadError("'<path>': <what>").
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what);

// "0.5", "1e+12", "nan" — numbers in messages (%.6g).
std::string format_number(double x);

// "12.0 MiB", "3 bytes" — sizes in messages.
std::string format_bytes(std::uint64_t bytes);

// nx·ny·nz after checking each is ≥ 2 (fail: "<what> is a×b×c: at least 2 samples per axis are needed").
std::uint64_t checked_voxel_count(const std::filesystem::path& path, const std::array<std::int64_t, 3>& dims);

// Fails unless voxels·(4 + options.extra_bytes_per_voxel) + buffer_bytes fits options.memory_budget_bytes; the
// message names the dimensions, each part, the sum and the budget. `dims` are x, y, z samples (voxels = their product,
// from checked_voxel_count).
void check_budget(const std::filesystem::path& path, const std::array<std::int64_t, 3>& dims, std::uint64_t voxels,
                  std::uint64_t buffer_bytes, const VolumeLoadOptions& options);

// Bytes of options.memory_budget_bytes left after `voxels` samples (4 + extra_bytes_per_voxel each), 0 when none.
std::uint64_t budget_left(std::uint64_t voxels, const VolumeLoadOptions& options);

// Fails unless `index_to_world` (millimetres, affine) for a dims[0]×dims[1]×dims[2] volume is finite, non-singular,
// has voxel axes from kMinVoxelSpacingMillimetres to kMaxVoxelSpacingMillimetres long, and puts the 8 corner voxels
// within ±kMaxVolumeWorldMillimetres. `field` names where the matrix came from ("the sform (srow_x/y/z)").
void check_index_to_world(const std::filesystem::path& path, const std::array<int, 3>& dims,
                          const glm::dmat4& index_to_world, const std::string& field);

ScalarVolume load_nifti(const std::filesystem::path& path, const VolumeLoadOptions& options);
ScalarVolume load_dicom(const std::filesystem::path& path, const VolumeLoadOptions& options);
ScalarVolume load_inv3(const std::filesystem::path& path, const VolumeLoadOptions& options);

// One DICOM image file on its own, through the checks and decoding a series' slice goes through (walk, header tags,
// pixel format, decode): rows·columns floats, rescaled, row by row. load_volume needs two slices; the DICOM fuzz
// target runs this on its one input as well. Throws VolumeLoadError.
std::vector<float> load_dicom_slice(const std::filesystem::path& file, const VolumeLoadOptions& options);

}  // namespace trispline::core::volume_io
