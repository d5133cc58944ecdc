// load_volume: dispatch on the path (folder or extension) and the checks every reader shares.
#include "core/volume/volume_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <system_error>
#include <vector>

#include "core/base/text.h"
#include "core/volume/volume_io_formats.h"

namespace trispline::core {

namespace volume_io {

std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

void fail(const std::filesystem::path& path, const std::string& what) {
  throw VolumeLoadError(quoted(path) + ": " + what);
}

std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string format_bytes(std::uint64_t bytes) {
  char text[64];
  if (bytes < 1024) {
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  } else {
    const char* unit[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = static_cast<double>(bytes) / 1024.0;
    int u = 0;
    while (value >= 1024.0 && u < 5) value /= 1024.0, ++u;
    std::snprintf(text, sizeof text, "%.1f %s", value, unit[u]);
  }
  return text;
}

std::uint64_t checked_voxel_count(const std::filesystem::path& path, const std::array<std::int64_t, 3>& dims) {
  const std::string shape = std::to_string(dims[0]) + "×" + std::to_string(dims[1]) + "×" + std::to_string(dims[2]);
  for (const std::int64_t d : dims)
    if (d < 2) fail(path, "the volume is " + shape + " samples: at least 2 per axis are needed");
  constexpr std::int64_t kMaxAxis = std::numeric_limits<int>::max();
  for (const std::int64_t d : dims)
    if (d > kMaxAxis)
      fail(path, "the volume is " + shape + " samples: an axis is longer than " + std::to_string(kMaxAxis));
  // Each factor < 2^31: the product of three fits 2^93, so check step by step.
  std::uint64_t n = static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(dims[1]);
  if (n > std::numeric_limits<std::uint64_t>::max() / static_cast<std::uint64_t>(dims[2]))
    fail(path, "the volume is " + shape + " samples: too many to count");
  return n * static_cast<std::uint64_t>(dims[2]);
}

namespace {

// a + b and a · b, saturating at the largest uint64 (budget arithmetic on header values).
std::uint64_t sat_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max() : a + b;
}
std::uint64_t sat_mul(std::uint64_t a, std::uint64_t b) {
  return b != 0 && a > std::numeric_limits<std::uint64_t>::max() / b ? std::numeric_limits<std::uint64_t>::max()
                                                                     : a * b;
}

std::string shape_text(const std::array<std::int64_t, 3>& dims) {
  return std::to_string(dims[0]) + "×" + std::to_string(dims[1]) + "×" + std::to_string(dims[2]);
}

}  // namespace

std::uint64_t budget_left(std::uint64_t voxels, const VolumeLoadOptions& options) {
  const std::uint64_t held = sat_mul(voxels, sat_add(4, options.extra_bytes_per_voxel));
  return held >= options.memory_budget_bytes ? 0 : options.memory_budget_bytes - held;
}

void check_budget(const std::filesystem::path& path, const std::array<std::int64_t, 3>& dims, std::uint64_t voxels,
                  std::uint64_t buffer_bytes, const VolumeLoadOptions& options) {
  const std::uint64_t limit = options.memory_budget_bytes;
  const std::uint64_t float_bytes = sat_mul(voxels, 4);
  const std::uint64_t extra_bytes = sat_mul(voxels, options.extra_bytes_per_voxel);
  const std::uint64_t total = sat_add(sat_add(float_bytes, extra_bytes), buffer_bytes);
  if (total > limit) {
    std::string parts = format_bytes(float_bytes) + " as float";
    if (options.extra_bytes_per_voxel > 0)
      parts += " + " + format_bytes(extra_bytes) + " (" + std::to_string(options.extra_bytes_per_voxel) +
               " bytes a voxel) for what follows the load";
    parts += " + " + format_bytes(buffer_bytes) + " of file buffers";
    fail(path, "the volume is " + shape_text(dims) + " samples (" + std::to_string(voxels) + "): it needs " + parts +
                   " = " + format_bytes(total) + " (" + std::to_string(total) + " bytes), over the memory budget of " +
                   format_bytes(limit) + " (" + std::to_string(limit) + " bytes)");
  }
  if (voxels > std::vector<float>().max_size()) fail(path, std::to_string(voxels) + " samples: too many to hold");
}

void check_index_to_world(const std::filesystem::path& path, const std::array<int, 3>& dims,
                          const glm::dmat4& index_to_world, const std::string& field) {
  const glm::dmat4& m = index_to_world;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(m[c][r]))
        fail(path, field + ": the voxel-to-world matrix holds " + format_number(m[c][r]) + " (column " +
                       std::to_string(c) + ", row " + std::to_string(r) + " in millimetres): not finite");
  const glm::dmat3 a(m);
  // Singular relative to the axes' own lengths (a volume of 1 × 1000 × 1 mm voxels is not near singular).
  const double volume = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  const double det = glm::determinant(a);
  if (!std::isfinite(det) || !(volume > 0.0) || !(std::abs(det) > 1e-12 * volume))
    fail(path, field + ": the voxel-to-world matrix is singular (determinant " + format_number(det) +
                   "; a zero or repeated voxel axis)");
  for (int c = 0; c < 3; ++c) {
    const double spacing = glm::length(a[c]);
    if (!(spacing >= kMinVoxelSpacingMillimetres && spacing <= kMaxVoxelSpacingMillimetres))
      fail(path, field + ": the voxel axis " + "ijk"[c] + " is " + format_number(spacing) + " mm long, outside the " +
                     format_number(kMinVoxelSpacingMillimetres) + " to " + format_number(kMaxVoxelSpacingMillimetres) +
                     " mm a voxel may span");
  }
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 ijk((corner & 1) ? dims[0] - 1 : 0, (corner & 2) ? dims[1] - 1 : 0,
                         (corner & 4) ? dims[2] - 1 : 0);
    const glm::dvec3 w(m * glm::dvec4(ijk, 1.0));
    for (int r = 0; r < 3; ++r)
      if (!(std::abs(w[r]) <= kMaxVolumeWorldMillimetres))
        fail(path, field + ": voxel (" + format_number(ijk.x) + ", " + format_number(ijk.y) + ", " +
                       format_number(ijk.z) + ") lies at " + format_number(w.x) + ", " + format_number(w.y) + ", " +
                       format_number(w.z) + " mm, beyond ±" + format_number(kMaxVolumeWorldMillimetres) +
                       " mm (1000 km) from the origin");
  }
}

}  // namespace volume_io

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

enum class VolumeFormat { kNone, kNifti, kDicom, kInv3 };

VolumeFormat format_of_name(const std::filesystem::path& p) {
  const std::string name = ascii_lower(p.filename().string());
  if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) return VolumeFormat::kNifti;
  if (ends_with(name, ".dcm")) return VolumeFormat::kDicom;
  if (ends_with(name, ".inv3")) return VolumeFormat::kInv3;
  return VolumeFormat::kNone;
}

}  // namespace

bool is_volume_path(const std::filesystem::path& p) {
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec)) return true;
  return format_of_name(p) != VolumeFormat::kNone;
}

ScalarVolume load_volume(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  using volume_io::fail;
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(path, "no such file or folder");
  const VolumeFormat format = std::filesystem::is_directory(status) ? VolumeFormat::kDicom : format_of_name(path);
  if (format == VolumeFormat::kNone)
    fail(path, "not a volume file (expected .nii, .nii.gz, .inv3, .dcm or a DICOM series folder)");
  if (!std::filesystem::is_directory(status) && !std::filesystem::is_regular_file(status))
    fail(path, "not a regular file");
  ScalarVolume v;
  try {
    switch (format) {
      case VolumeFormat::kNifti:
        v = volume_io::load_nifti(path, options);
        break;
      case VolumeFormat::kDicom:
        v = volume_io::load_dicom(path, options);
        break;
      case VolumeFormat::kInv3:
        v = volume_io::load_inv3(path, options);
        break;
      case VolumeFormat::kNone:
        break;
    }
  } catch (const std::bad_alloc&) {  // within the budget, but the machine has less memory than the budget allows
    fail(path, "out of memory (memory budget " + volume_io::format_bytes(options.memory_budget_bytes) + ")");
  }
  v.source = path.string();
  if (const std::string why = scalar_volume_error(v); !why.empty()) fail(path, why);
  return v;
}

}  // namespace trispline::core
