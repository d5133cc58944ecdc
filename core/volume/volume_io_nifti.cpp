// NIfTI-1 single files (.nii, .nii.gz) through niftilib.
//
// The file is read through zlib's gz stream (.nii.gz) or stdio (.nii). The 348-byte header is checked here before
// niftilib converts it (nifti_convert_nhdr2nim: byte order, the qform quaternion, the sform rows): niftilib would
// otherwise turn a zero dimension into 1, clamp a short vox_offset, follow an ANALYZE or two-file header to a second
// file, replace a zero or NaN pixdim by 1, and normalise a quaternion longer than 1. The geometry and the memory
// budget are checked on the header before a sample is read or inflated.
// The samples are read here too, in blocks, not by nifti_image_load: niftilib's reader replaces NaN and Inf floats
// by 0 without telling, and a volume with non-finite samples must be refused.
#include <nifti1_io.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

// The file's bytes in order: a gzip stream through zlib (.nii.gz) or the plain file (.nii).
class NiftiStream {
 public:
  NiftiStream(const std::filesystem::path& path, bool gz) : path_(path), gz_(gz) {
    if (gz_)
      gz_file_ = gzopen(path.c_str(), "rb");
    else
      plain_ = std::fopen(path.c_str(), "rb");
    if (gz_ ? gz_file_ == nullptr : plain_ == nullptr) fail(path, "cannot open the file");
    if (gz_) gzbuffer(gz_file_, 128 * 1024);
  }
  ~NiftiStream() {
    if (gz_file_) gzclose(gz_file_);
    if (plain_) std::fclose(plain_);
  }
  NiftiStream(const NiftiStream&) = delete;
  NiftiStream& operator=(const NiftiStream&) = delete;

  // Up to `size` bytes (≤ kStreamBlockBytes); fewer only at the end of the data. A damaged gzip stream (bad data, a
  // CRC or length that does not match) fails naming zlib's reason and how far the bytes were good; `what` says what
  // was being read ("the samples").
  std::size_t read(void* out, std::size_t size, const std::string& what) {
    if (!gz_) return std::fread(out, 1, size, plain_);
    const int got = gzread(gz_file_, out, static_cast<unsigned>(size));
    if (got < 0) {
      int code = Z_OK;
      std::string reason = gzerror(gz_file_, &code);
      const std::string prefix = path_.string() + ": ";  // zlib starts its message with the file name
      if (reason.rfind(prefix, 0) == 0) reason.erase(0, prefix.size());
      // zlib checks the trailer as soon as its buffer reaches the end, which for a small file is the first read.
      const bool trailer = reason.find("incorrect data check") != std::string::npos ||
                           reason.find("incorrect length check") != std::string::npos;
      if (trailer)
        fail(path_,
             "the gzip stream's check at its end (CRC-32 and length) does not match its data: the file is "
             "damaged (zlib: " +
                 reason + ")");
      fail(path_, "the gzip stream is damaged in " + what + " (zlib: " + reason + "; " + std::to_string(done_) +
                      " bytes decompressed before the call that failed)");
    }
    done_ += static_cast<std::uint64_t>(got);
    return static_cast<std::size_t>(got);
  }

  // Skips forward to byte `offset` of the (decompressed) data; false past its end.
  bool seek(std::uint64_t offset) {
    if (!gz_) return fseeko(plain_, static_cast<off_t>(offset), SEEK_SET) == 0;
    std::vector<unsigned char> scratch(kStreamBlockBytes);
    while (done_ < offset) {
      const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(scratch.size(), offset - done_));
      if (read(scratch.data(), want, "the bytes before vox_offset") != want) return false;
    }
    return true;
  }

  // For a gzip stream: reads on past the samples (at most kStreamBlockBytes) so that zlib checks the stream's CRC and
  // length.
  void check_gzip_trailer() {
    if (!gz_) return;
    std::vector<unsigned char> scratch(64 * 1024);
    std::uint64_t after = 0;  // bytes after the samples: a few are harmless, a long tail is not inflated
    while (after < kStreamBlockBytes) {
      const std::size_t got = read(scratch.data(), scratch.size(), "the end of the stream");
      if (got == 0) break;
      after += got;
    }
  }

 private:
  std::filesystem::path path_;
  bool gz_;
  gzFile gz_file_ = nullptr;
  std::FILE* plain_ = nullptr;
  std::uint64_t done_ = 0;  // decompressed bytes read so far (gzip)
};

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

// The header's voxel-to-world matrix in millimetres, after refusing what niftilib would repair silently: a pixdim
// that is zero, negative or not finite where it is used (the qform's scales, or diag(pixdim)), a quaternion that is
// not finite or longer than 1, a qfac (pixdim[0]) or qoffset that is not finite. `h` is in this machine's byte order,
// `raw` as read (niftilib converts it again).
glm::dmat4 nifti_index_to_world(const std::filesystem::path& path, const nifti_1_header& h, const nifti_1_header& raw,
                                const std::array<int, 3>& dims) {
  const bool sform = h.sform_code > 0, qform = !sform && h.qform_code > 0;
  std::string field =
      sform   ? "the sform (srow_x, srow_y, srow_z; sform_code " + std::to_string(h.sform_code) + ")"
      : qform ? "the qform (quatern_b/c/d, qoffset_x/y/z, pixdim; qform_code " + std::to_string(h.qform_code) + ")"
              : "pixdim[1..3] (no sform or qform)";
  if (!sform) {
    for (int d = 1; d <= 3; ++d)
      if (!(std::isfinite(h.pixdim[d]) && h.pixdim[d] > 0.0f))
        fail(path, "pixdim[" + std::to_string(d) + "] is " + format_number(h.pixdim[d]) + " in " + field +
                       ": a voxel size must be a positive finite number");
  }
  if (qform) {
    const double b = h.quatern_b, c = h.quatern_c, d = h.quatern_d;
    if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d) || b * b + c * c + d * d > 1.0 + 1e-5)
      fail(path, "the qform quaternion (quatern_b, quatern_c, quatern_d) = (" + format_number(b) + ", " +
                     format_number(c) + ", " + format_number(d) + ") is not part of a unit quaternion");
    if (!std::isfinite(h.qoffset_x) || !std::isfinite(h.qoffset_y) || !std::isfinite(h.qoffset_z))
      fail(path, "the qform offset (qoffset_x, qoffset_y, qoffset_z) is not finite");
    if (!std::isfinite(h.pixdim[0])) fail(path, "pixdim[0] (the qform's qfac) is not finite");
  }
  // niftilib's reading of the header: byte order, qform (quaternion, qfac), sform.
  std::unique_ptr<nifti_image, NiftiImageFree> nim(nifti_convert_nhdr2nim(raw, nullptr));
  if (!nim) fail(path, "niftilib cannot convert the header");
  const mat44& m = sform ? nim->sto_xyz : nim->qto_xyz;  // qto_xyz is diag(pixdim) when qform_code ≤ 0
  const double mm = millimetres_per_unit(h.xyzt_units);
  glm::dmat4 index_to_world(1.0);
  for (int col = 0; col < 4; ++col)
    for (int r = 0; r < 3; ++r) index_to_world[col][r] = static_cast<double>(m.m[r][col]) * mm;
  if (mm != 1.0) field += " in " + std::string(mm > 1.0 ? "metres" : "microns") + " (xyzt_units)";
  check_index_to_world(path, dims, index_to_world, field);
  return index_to_world;
}

}  // namespace

ScalarVolume load_nifti(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  const bool gz = name_ends_with_gz(path);
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot read the file size: " + ec.message());
  NiftiStream file(path, gz);

  nifti_1_header raw;
  static_assert(sizeof raw == 348, "the NIfTI-1 header is 348 bytes");
  const std::size_t got = file.read(&raw, sizeof raw, "the header");
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
  const std::array<std::int64_t, 3> dims{h.dim[1], h.dim[2], h.dim[3]};
  const std::uint64_t voxels = checked_voxel_count(path, dims);

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

  ScalarVolume v;
  v.dims = {h.dim[1], h.dim[2], h.dim[3]};
  v.index_to_world = nifti_index_to_world(path, h, raw, v.dims);
  v.frame = "RAS";  // NIfTI's world is RAS+ whether sform or qform gives it
  check_budget(path, dims, voxels, kStreamBlockBytes, options);
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

  // Samples, streamed in blocks from vox_offset (on a gzip stream, seeking decompresses up to it).
  if (!file.seek(data_offset))
    fail(path,
         "vox_offset " + std::to_string(data_offset) + " is past the end of the file" + (gz ? " (decompressed)" : ""));
  v.values.reserve(voxels);
  const std::size_t block = kStreamBlockBytes / static_cast<std::size_t>(nbyper) * static_cast<std::size_t>(nbyper);
  std::vector<unsigned char> buffer(static_cast<std::size_t>(std::min<std::uint64_t>(block, data_bytes)));
  std::uint64_t done = 0;
  while (done < data_bytes) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), data_bytes - done));
    const std::size_t read = file.read(buffer.data(), want, "the samples");
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
  file.check_gzip_trailer();
  return v;
}

}  // namespace trispline::core::volume_io
