// trispline::core volume files — CT/MRI volumes read into a ScalarVolume, whole or refused.
//
//   is_volume_path  whether load_volume would try a path (by extension, or a folder)
//   load_volume     .nii / .nii.gz (niftilib), a DICOM series folder or one of its .dcm files (GDCM), an InVesalius
//                   .inv3 project (libarchive + tinyxml2) → ScalarVolume
//
// Errors: VolumeLoadError (a std::runtime_error) whose message starts with the file or folder and says what is
// wrong: not found, not a volume, truncated, bad dimensions, unsupported datatype / transfer syntax, over the memory
// budget (checked on the header's dimensions before samples are read or inflated), inconsistent slices, non-finite
// samples, a voxel-to-world matrix that is not finite, singular or beyond kMaxVolumeWorldMillimetres, a DICOM data set
// whose element lengths or nesting do not fit the file, a series entry resolving outside its folder. Nothing is
// returned half-read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "core/volume/scalar_volume.h"

namespace trispline::core {

struct VolumeLoadOptions {
  // Bytes a load may hold at once: the decoded float samples (4 per voxel) plus the file buffers it reads through
  // (DICOM: two copies of the largest slice file; NIfTI and .inv3 stream the samples in blocks of at most 1 MiB).
  // Checked against the file's dimensions before anything of that size is allocated.
  std::uint64_t memory_budget_bytes = 4ull << 30;
  // Bytes per voxel the caller will spend after the load (e.g. preparing the spline and its tables), counted with the
  // 4 float bytes in the budget check on the header's dimensions: a file whose volume the caller could not go on to
  // use is refused before its samples are read or inflated.
  std::size_t extra_bytes_per_voxel = 0;
};

// Geometry bounds every loaded volume meets (checked on the header before samples are read): each voxel axis of
// index_to_world is from kMinVoxelSpacingMillimetres to kMaxVoxelSpacingMillimetres long, and the world positions of
// the volume's 8 corner voxels are within ±kMaxVolumeWorldMillimetres on each axis (1000 km: beyond any scanner, far
// inside the scene's 1e12 world-unit limit, so meshes and silhouettes made from the volume stay finite in float).
inline constexpr double kMinVoxelSpacingMillimetres = 1e-6;  // 1 nm
inline constexpr double kMaxVoxelSpacingMillimetres = 1e6;   // 1 km
inline constexpr double kMaxVolumeWorldMillimetres = 1e9;

class VolumeLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// True for a path load_volume dispatches on: a name ending in .nii, .nii.gz, .inv3 or .dcm (any case), or an
// existing folder (a DICOM series). Only the name and whether it is a folder are looked at, not the content.
bool is_volume_path(const std::filesystem::path& p);

// Reads a volume: all samples as float, x fastest (see ScalarVolume), index_to_world in millimetres.
//   .nii .nii.gz  NIfTI-1 single file, through niftilib. dim[0] 3 (or up to 7 with dim[4..] all 1), each of
//                 dim[1..3] ≥ 2; datatypes uint8, int8, int16, uint16, int32, uint32, float32, float64.
//                 index_to_world: the sform when sform_code > 0, else the qform when qform_code > 0, else
//                 diag(pixdim[1..3]); scaled to millimetres by xyzt_units (metres, microns). Refused, not repaired:
//                 pixdim[1..3] not finite and positive where used (qform, diag), a qform quaternion that is not
//                 finite or longer than 1. Samples scaled by scl_slope / scl_inter (slope 0: none). A damaged gzip
//                 stream is refused with zlib's reason. units "", modality "".
//   folder, .dcm  one DICOM series through GDCM: a folder's single-frame images (several series are refused, each
//                 listed), or for a .dcm file the images of its folder in its own series. Every entry read must
//                 resolve (symlinks, "..") inside the folder, and every file's element headers are walked before
//                 GDCM parses it (lengths within the file, undefined lengths terminated, nesting ≤ 32, a deflated
//                 data set inflated to count its size within the budget first). Slices sorted by Image
//                 Position (Patient) along the normal of Image Orientation (Patient); index_to_world columns: row
//                 direction × column spacing, column direction × row spacing (Pixel Spacing), the mean step between
//                 consecutive slice positions (along the normal but for a tilted gantry), and the first slice's
//                 position. Refused: fewer than 2 slices, different sizes or orientations, two slices at one
//                 position, steps differing from their mean by more than 1 %, multi-frame or colour images, a
//                 transfer syntax GDCM cannot decode, Bits Stored 0 or above Bits Allocated, Pixel Data holding fewer
//                 samples than Rows × Columns. Samples: stored value × Rescale Slope + Rescale Intercept of
//                 each slice; units "HU" for modality CT, else ""; modality from (0008,0060).
//   .inv3         InVesalius 3 project: a tar (gzip'd or not) holding main.plist (XML plist: matrix filename, shape
//                 [z, y, x], dtype int16; spacing [x, y, z] mm) and the matrix file, raw int16 little-endian of
//                 exactly that shape, x fastest. index_to_world = diag(spacing), voxel (0,0,0) at the origin (the
//                 frame InVesalius draws the project in). units "HU" and modality "CT" unless the plist names
//                 another modality (then that modality, units "").
// The result passes scalar_volume_error; source = path. Throws VolumeLoadError.
ScalarVolume load_volume(const std::filesystem::path& path, const VolumeLoadOptions& options = {});

}  // namespace trispline::core
