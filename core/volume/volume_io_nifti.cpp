// NIfTI-1 single files (.nii, .nii.gz) through niftilib.
//
// The 348-byte header is read through niftilib's znzlib stream (gzip or plain) and checked here before niftilib
// converts it (nifti_convert_nhdr2nim: byte order, the qform quaternion, the sform rows): niftilib would otherwise
// turn a zero dimension into 1, clamp a short vox_offset, and follow an ANALYZE or two-file header to a second file.
// The samples are read here too, in blocks, not by nifti_image_load: niftilib's reader replaces NaN and Inf floats
// by 0 without telling, and a volume with non-finite samples must be refused.
#include <nifti1_io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

struct ZnzCloser {
  void operator()(znzptr* f) const {
    znzFile file = f;
    znzclose(file);
  }
};
using ZnzPtr = std::unique_ptr<znzptr, ZnzCloser>;

struct NiftiImageFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};

bool name_ends_with_gz(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  if (name.size() < 3) return false;
  name = name.substr(name.size() - 3);
  return name[0] == '.' && (name[1] | 0x20) == 'g' && (name[2] | 0x20) == 'z';
}

// Bytes per sample of a supported datatype, 0 otherwise.
int bytes_per_sample(int datatype) {
  switch (datatype) {
    case DT_UINT8:
    case DT_INT8:
      return 1;
    case DT_INT16:
    case DT_UINT16:
      return 2;
    case DT_INT32:
    case DT_UINT32:
    case DT_FLOAT32:
      return 4;
    case DT_FLOAT64:
      return 8;
    default:
      return 0;
  }
}

template <typename T>
T load_sample(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// One stored sample (already in this machine's byte order) as double.
double sample_value(int datatype, const unsigned char* p) {
  switch (datatype) {
    case DT_UINT8:
      return *p;
    case DT_INT8:
      return static_cast<signed char>(*p);
    case DT_INT16:
      return load_sample<std::int16_t>(p);
    case DT_UINT16:
      return load_sample<std::uint16_t>(p);
    case DT_INT32:
      return load_sample<std::int32_t>(p);
    case DT_UINT32:
      return load_sample<std::uint32_t>(p);
    case DT_FLOAT32:
      return load_sample<float>(p);
    default:
      return load_sample<double>(p);
  }
}

// Millimetres per unit of the file's spatial unit (xyzt_units & 7): metres, microns; unknown or mm → 1.
double millimetres_per_unit(int xyzt_units) {
  switch (XYZT_TO_SPACE(xyzt_units)) {
    case NIFTI_UNITS_METER:
      return 1000.0;
    case NIFTI_UNITS_MICRON:
      return 0.001;
    default:
      return 1.0;
  }
}

}  // namespace

ScalarVolume load_nifti(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  const std::string name = path.string();
  const bool gz = name_ends_with_gz(path);
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot read the file size: " + ec.message());

  ZnzPtr file(znzopen(name.c_str(), "rb", gz ? 1 : 0));
  if (!file) fail(path, "cannot open the file");

  nifti_1_header raw;
  static_assert(sizeof raw == 348, "the NIfTI-1 header is 348 bytes");
  const std::size_t got = znzread(&raw, 1, sizeof raw, file.get());
  if (got < sizeof raw)
    fail(path, "truncated: " + std::to_string(got) + " bytes" + (gz ? " after decompression" : "") +
                   ", less than a NIfTI-1 header (348 bytes)");

  // Byte order from sizeof_hdr (348 either way round); NIfTI-2 says 540.
  nifti_1_header h = raw;
  int size_field = h.sizeof_hdr;
  bool swapped = false;
  if (size_field != 348) {
    nifti_swap_4bytes(1, &size_field);
    swapped = size_field == 348;
    if (!swapped) {
      int other = h.sizeof_hdr;
      nifti_swap_4bytes(1, &other);
      if (h.sizeof_hdr == 540 || other == 540) fail(path, "a NIfTI-2 file: only NIfTI-1 is read");
      fail(path, "not a NIfTI-1 file (its header size field is " + std::to_string(h.sizeof_hdr) + ", not 348)");
    }
    swap_nifti_header(&h, 1);
  }
  if (std::memcmp(h.magic, "ni1", 4) == 0)
    fail(path, "the header of a two-file NIfTI pair (.hdr + .img): only single-file .nii / .nii.gz is read");
  if (std::memcmp(h.magic, "n+1", 4) != 0) fail(path, "not a NIfTI-1 file (no \"n+1\" magic; ANALYZE 7.5?)");

  // Dimensions: 3-D, or more dimensions that are all 1 beyond z.
  const int ndim = h.dim[0];
  if (ndim < 3 || ndim > 7)
    fail(path, "dim[0] is " + std::to_string(ndim) + ": a volume needs 3 dimensions (dim[0] from 3 to 7)");
  for (int d = 4; d <= ndim; ++d)
    if (h.dim[d] != 1)
      fail(path, "dim[" + std::to_string(d) + "] is " + std::to_string(h.dim[d]) +
                     ": a time series or vector volume, only one 3-D volume is read");
  const std::uint64_t voxels = checked_voxel_count(path, {h.dim[1], h.dim[2], h.dim[3]});

  const int nbyper = bytes_per_sample(h.datatype);
  if (nbyper == 0)
    fail(path, std::string("datatype ") + nifti_datatype_string(h.datatype) + " (" + std::to_string(h.datatype) +
                   ") is not supported (uint8, int8, int16, uint16, int32, uint32, float32, float64 are)");
  if (h.bitpix != 8 * nbyper)
    fail(path, "bitpix is " + std::to_string(h.bitpix) + " for datatype " + nifti_datatype_string(h.datatype) + " (" +
                   std::to_string(8 * nbyper) + " expected)");

  const double vox_offset = h.vox_offset;
  if (!std::isfinite(vox_offset) || vox_offset < 352.0 || vox_offset != std::floor(vox_offset) ||
      vox_offset > std::numeric_limits<int>::max())
    fail(path, "vox_offset " + format_number(vox_offset) +
                   " is not a whole number of bytes from 352 (the header and its extender) on");
  const std::uint64_t data_offset = static_cast<std::uint64_t>(vox_offset);

  const double slope = h.scl_slope, inter = h.scl_inter;
  if (!std::isfinite(slope) || (slope != 0.0 && !std::isfinite(inter)))
    fail(path, "scl_slope / scl_inter are not finite numbers");

  check_budget(path, voxels, kStreamBlockBytes, options);
  if (voxels > std::numeric_limits<std::uint64_t>::max() / 8) fail(path, "too many samples");
  const std::uint64_t data_bytes = voxels * static_cast<std::uint64_t>(nbyper);
  if (!gz) {
    if (file_size < data_offset)
      fail(path, "vox_offset " + std::to_string(data_offset) + " is past the end of the file (" +
                     std::to_string(file_size) + " bytes)");
    if (file_size - data_offset < data_bytes)
      fail(path, "truncated: " + std::to_string(file_size - data_offset) + " bytes of samples after vox_offset " +
                     std::to_string(data_offset) + ", " + std::to_string(data_bytes) + " needed for " +
                     std::to_string(h.dim[1]) + "×" + std::to_string(h.dim[2]) + "×" + std::to_string(h.dim[3]) + " " +
                     nifti_datatype_string(h.datatype));
  }

  // niftilib's reading of the header: byte order, qform (quaternion, qfac), sform, pixdim.
  std::unique_ptr<nifti_image, NiftiImageFree> nim(nifti_convert_nhdr2nim(raw, nullptr));
  if (!nim) fail(path, "niftilib cannot convert the header");
  const mat44& m = h.sform_code > 0 ? nim->sto_xyz : nim->qto_xyz;  // qto_xyz is diag(pixdim) when qform_code ≤ 0
  const double mm = millimetres_per_unit(h.xyzt_units);

  ScalarVolume v;
  v.dims = {h.dim[1], h.dim[2], h.dim[3]};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) v.index_to_world[c][r] = static_cast<double>(m.m[r][c]) * mm;
  v.index_to_world[0][3] = v.index_to_world[1][3] = v.index_to_world[2][3] = 0.0;
  v.index_to_world[3][3] = 1.0;

  // Samples, streamed in blocks from vox_offset (znzseek on a gzip stream decompresses up to it).
  if (znzseek(file.get(), static_cast<long>(data_offset), SEEK_SET) < 0)
    fail(path, "vox_offset " + std::to_string(data_offset) + " is past the end of the file");
  v.values.reserve(voxels);
  const std::size_t block = kStreamBlockBytes / static_cast<std::size_t>(nbyper) * static_cast<std::size_t>(nbyper);
  std::vector<unsigned char> buffer(static_cast<std::size_t>(std::min<std::uint64_t>(block, data_bytes)));
  std::uint64_t done = 0;
  while (done < data_bytes) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), data_bytes - done));
    const std::size_t read = znzread(buffer.data(), 1, want, file.get());
    if (read != want)
      fail(path, "truncated: the samples end after " + std::to_string(done + read) + " of " +
                     std::to_string(data_bytes) + " bytes" + (gz ? " (decompressed)" : ""));
    if (swapped && nbyper > 1) nifti_swap_Nbytes(want / nbyper, nbyper, buffer.data());
    for (std::size_t i = 0; i < want; i += static_cast<std::size_t>(nbyper)) {
      const double s = sample_value(h.datatype, buffer.data() + i);
      v.values.push_back(to_float(slope != 0.0 ? s * slope + inter : s));
    }
    done += want;
  }
  return v;
}

}  // namespace trispline::core::volume_io
