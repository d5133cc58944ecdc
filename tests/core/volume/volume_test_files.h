// Volume files the loader tests write themselves: NIfTI through niftilib, DICOM slices through GDCM or byte by byte
// (DicomBytes: what GDCM would not write), InVesalius .inv3 projects (tar / tar.gz through libarchive, main.plist as
// text), deflate bombs streamed through zlib (write_deflated), a temporary folder per test, and the checks the
// hostile-file tests share (volume_load_error, peak_rss_bytes).
#pragma once

#include <archive.h>
#include <archive_entry.h>
#include <gdcmAttribute.h>
#include <gdcmImage.h>
#include <gdcmImageChangeTransferSyntax.h>
#include <gdcmImageReader.h>
#include <gdcmImageWriter.h>
#include <gdcmMediaStorage.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>
#include <gdcmUIDGenerator.h>
#include <gdcmWriter.h>
#include <gtest/gtest.h>
#include <nifti1_io.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/volume/volume_io.h"

namespace trispline::test {

// A fresh folder under the system temp folder, named after the running test, removed at the end.
class TempFolder {
 public:
  TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("trispline_volume_io_" + std::string(info->test_suite_name()) +
                                                      "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::vector<unsigned char> read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& p, const void* data, std::size_t size) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

inline void write_bytes(const std::filesystem::path& p, const std::vector<unsigned char>& bytes) {
  write_bytes(p, bytes.data(), bytes.size());
}

// The message of the VolumeLoadError load_volume throws (a test failure if it loads or throws something else); it
// must name the file or folder.
inline std::string volume_load_error(const std::filesystem::path& p,
                                     const trispline::core::VolumeLoadOptions& options = {}) {
  try {
    const trispline::core::ScalarVolume v = trispline::core::load_volume(p, options);
    ADD_FAILURE() << p << " loaded as " << v.dims[0] << "×" << v.dims[1] << "×" << v.dims[2];
  } catch (const trispline::core::VolumeLoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(p.filename().string()), std::string::npos) << "the message must name the file: " << what;
    return what;
  }
  return {};
}

// The process's peak resident set so far (getrusage), bytes.
inline std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

// Deflates `head` followed by `zeros` zero bytes into `p`, streaming (nothing of that size is held): gzip framing
// when `gzip`, else a raw deflate stream (DICOM's deflated transfer syntax) appended after `prefix`.
inline void write_deflated(const std::filesystem::path& p, const std::vector<unsigned char>& prefix,
                           const std::vector<unsigned char>& head, std::uint64_t zeros, bool gzip,
                           const std::vector<unsigned char>& tail = {}) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(prefix.data()), static_cast<std::streamsize>(prefix.size()));
  z_stream z{};
  if (deflateInit2(&z, 6, Z_DEFLATED, gzip ? 31 : -15, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2 failed");
  std::vector<unsigned char> block(1 << 20), compressed(1 << 20);
  const auto pump = [&](const unsigned char* data, std::size_t size, int flush) {
    z.next_in = const_cast<unsigned char*>(data);
    z.avail_in = static_cast<uInt>(size);
    do {
      z.next_out = compressed.data();
      z.avail_out = static_cast<uInt>(compressed.size());
      deflate(&z, flush);
      out.write(reinterpret_cast<const char*>(compressed.data()),
                static_cast<std::streamsize>(compressed.size() - z.avail_out));
    } while (z.avail_out == 0);
  };
  pump(head.data(), head.size(), Z_NO_FLUSH);
  for (std::uint64_t left = zeros; left > 0;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, block.size()));
    pump(block.data(), n, Z_NO_FLUSH);
    left -= n;
  }
  pump(tail.data(), tail.size(), Z_FINISH);
  deflateEnd(&z);
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

// ---------------------------------------------------------------------------------------------------------- NIfTI

// Writes a single-file NIfTI-1 (.nii or .nii.gz by the name) through niftilib: nx×ny×nz samples of `datatype`
// (`samples` holds nx·ny·nz of them in that type's bytes, x fastest). pixdim 1, no qform, no sform, no scaling
// unless `edit` sets them (it runs on the nifti_image before writing: set qto_xyz and call set_qform below, or
// sform_code + sto_xyz, scl_slope / scl_inter, xyz_units).
inline void write_nifti(const std::filesystem::path& p, std::array<int, 3> n, int datatype,
                        const std::vector<unsigned char>& samples, const std::function<void(nifti_image&)>& edit = {}) {
  const int dims[8] = {3, n[0], n[1], n[2], 1, 1, 1, 1};
  nifti_image* nim = nifti_make_new_nim(dims, datatype, 1);
  if (!nim) throw std::runtime_error("nifti_make_new_nim failed");
  const std::size_t bytes = static_cast<std::size_t>(nim->nvox) * static_cast<std::size_t>(nim->nbyper);
  if (samples.size() != bytes) throw std::runtime_error("write_nifti: wrong sample byte count");
  std::memcpy(nim->data, samples.data(), bytes);
  nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;
  nim->qform_code = 0;
  nim->sform_code = 0;
  if (edit) edit(*nim);
  if (nifti_set_filenames(nim, p.c_str(), 0, 1) != 0) throw std::runtime_error("nifti_set_filenames failed");
  nifti_image_write(nim);
  nifti_image_free(nim);
  if (!std::filesystem::exists(p)) throw std::runtime_error("niftilib did not write " + p.string());
}

// Sets the qform of `nim` from an affine (rotation × pixdim, optionally with a reflection: qfac) through
// niftilib's own quaternion encoding, as a writer does.
inline void set_qform(nifti_image& nim, const mat44& m, int code = NIFTI_XFORM_SCANNER_ANAT) {
  float qb, qc, qd, qx, qy, qz, dx, dy, dz, qfac;
  nifti_mat44_to_quatern(m, &qb, &qc, &qd, &qx, &qy, &qz, &dx, &dy, &dz, &qfac);
  nim.qform_code = code;
  nim.quatern_b = qb, nim.quatern_c = qc, nim.quatern_d = qd;
  nim.qoffset_x = qx, nim.qoffset_y = qy, nim.qoffset_z = qz;
  nim.qfac = qfac;
  nim.dx = nim.pixdim[1] = dx;
  nim.dy = nim.pixdim[2] = dy;
  nim.dz = nim.pixdim[3] = dz;
  nim.qto_xyz = m;
}

inline mat44 make_mat44(std::array<std::array<float, 4>, 3> rows) {
  mat44 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = rows[r][c];
  m.m[3][3] = 1.0f;
  return m;
}

template <typename T>
std::vector<unsigned char> as_bytes(const std::vector<T>& values) {
  std::vector<unsigned char> bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

// The header of an uncompressed .nii, to edit in place (patch_nifti_header).
inline nifti_1_header read_nifti_header(const std::filesystem::path& p) {
  const std::vector<unsigned char> bytes = read_bytes(p);
  nifti_1_header h;
  if (bytes.size() < sizeof h) throw std::runtime_error("short NIfTI file");
  std::memcpy(&h, bytes.data(), sizeof h);
  return h;
}

inline void patch_nifti_header(const std::filesystem::path& p, const std::function<void(nifti_1_header&)>& edit) {
  std::vector<unsigned char> bytes = read_bytes(p);
  nifti_1_header h;
  std::memcpy(&h, bytes.data(), sizeof h);
  edit(h);
  std::memcpy(bytes.data(), &h, sizeof h);
  write_bytes(p, bytes);
}

// ---------------------------------------------------------------------------------------------------------- DICOM

struct DicomSlice {
  std::string series_uid;
  std::string modality = "CT";
  int rows = 3, cols = 4;
  std::vector<std::int16_t> pixels;                     // rows·cols stored values, row by row
  glm::dvec3 position{0.0};                             // Image Position (Patient)
  std::array<double, 6> orientation{1, 0, 0, 0, 1, 0};  // Image Orientation (Patient): row, then column direction
  double spacing_x = 1.0, spacing_y = 1.0;              // between columns, between rows (Pixel Spacing is "y\x")
  double slope = 1.0, intercept = 0.0;
  int instance = 1;
  int bits_stored = 16;   // of 16 allocated
  bool is_signed = true;  // Pixel Representation 1
};

// One CT (or MR) Image Storage file through gdcm::ImageWriter: GDCM writes Image Position / Orientation, Pixel
// Spacing and Rescale Slope / Intercept from the gdcm::Image, the test sets the series, modality and instance.
// (For MR with a rescale other than 1, 0 GDCM writes an Enhanced MR image instead: the geometry then sits in
// functional groups.)
inline void write_dicom_slice(const std::filesystem::path& p, const DicomSlice& s) {
  gdcm::Trace::WarningOff();  // GDCM reports the attributes it fills in by default
  gdcm::ImageWriter writer;
  gdcm::Image& image = writer.GetImage();
  image.SetNumberOfDimensions(2);
  image.SetDimension(0, static_cast<unsigned>(s.cols));
  image.SetDimension(1, static_cast<unsigned>(s.rows));
  gdcm::PixelFormat format(gdcm::PixelFormat::INT16);
  format.SetBitsStored(static_cast<unsigned short>(s.bits_stored));
  format.SetHighBit(static_cast<unsigned short>(s.bits_stored - 1));
  format.SetPixelRepresentation(s.is_signed ? 1 : 0);
  image.SetPixelFormat(format);
  image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
  image.SetSpacing(0, s.spacing_x);
  image.SetSpacing(1, s.spacing_y);
  image.SetSpacing(2, 1.0);
  image.SetOrigin(0, s.position.x);
  image.SetOrigin(1, s.position.y);
  image.SetOrigin(2, s.position.z);
  image.SetDirectionCosines(s.orientation.data());
  image.SetSlope(s.slope);
  image.SetIntercept(s.intercept);
  gdcm::DataElement pixel_data(gdcm::Tag(0x7fe0, 0x0010));
  pixel_data.SetByteValue(reinterpret_cast<const char*>(s.pixels.data()),
                          static_cast<std::uint32_t>(s.pixels.size() * sizeof(std::int16_t)));
  image.SetDataElement(pixel_data);

  gdcm::DataSet& ds = writer.GetFile().GetDataSet();
  const gdcm::MediaStorage ms =
      s.modality == "MR" ? gdcm::MediaStorage::MRImageStorage : gdcm::MediaStorage::CTImageStorage;
  gdcm::DataElement sop_class(gdcm::Tag(0x0008, 0x0016));
  const char* ms_uid = gdcm::MediaStorage::GetMSString(ms);
  sop_class.SetByteValue(ms_uid, static_cast<std::uint32_t>(std::strlen(ms_uid)));
  sop_class.SetVR(gdcm::Attribute<0x0008, 0x0016>::GetVR());
  ds.Replace(sop_class);
  gdcm::Attribute<0x0008, 0x0060> modality;
  modality.SetValue(s.modality);
  ds.Replace(modality.GetAsDataElement());
  gdcm::Attribute<0x0020, 0x000e> series;
  series.SetValue(s.series_uid);
  ds.Replace(series.GetAsDataElement());
  gdcm::Attribute<0x0020, 0x0013> instance;
  instance.SetValue(s.instance);
  ds.Replace(instance.GetAsDataElement());

  writer.SetFileName(p.c_str());
  if (!writer.Write()) throw std::runtime_error("GDCM cannot write " + p.string());
}

// Re-encodes a DICOM file in place with another transfer syntax (gdcm::ImageChangeTransferSyntax). OpenJPEG's
// encoder crashes on images as small as 4×3: compress slices of 64×64 or so.
inline void recode_dicom(const std::filesystem::path& p, gdcm::TransferSyntax::TSType ts) {
  gdcm::ImageReader reader;
  reader.SetFileName(p.c_str());
  if (!reader.Read()) throw std::runtime_error("GDCM cannot read " + p.string());
  gdcm::ImageChangeTransferSyntax change;
  change.SetTransferSyntax(ts);
  change.SetInput(reader.GetImage());
  if (!change.Change()) throw std::runtime_error("GDCM cannot re-encode " + p.string());
  gdcm::ImageWriter writer;
  writer.SetFileName(p.c_str());
  writer.SetFile(reader.GetFile());
  writer.SetImage(change.GetOutput());
  if (!writer.Write()) throw std::runtime_error("GDCM cannot write " + p.string());
}

// Rewrites a DICOM file in place with its data set deflated (Deflated Explicit VR Little Endian).
inline void deflate_dicom(const std::filesystem::path& p) {
  gdcm::Reader reader;
  reader.SetFileName(p.c_str());
  if (!reader.Read()) throw std::runtime_error("GDCM cannot read " + p.string());
  reader.GetFile().GetHeader().SetDataSetTransferSyntax(gdcm::TransferSyntax::DeflatedExplicitVRLittleEndian);
  gdcm::Writer writer;
  writer.SetFileName(p.c_str());
  writer.SetFile(reader.GetFile());
  if (!writer.Write()) throw std::runtime_error("GDCM cannot write " + p.string());
}

// Replaces the first occurrence of `from` in the file by `to` (same length).
inline void patch_file_text(const std::filesystem::path& p, const std::string& from, const std::string& to) {
  std::vector<unsigned char> bytes = read_bytes(p);
  const std::string text(bytes.begin(), bytes.end());
  const std::size_t at = text.find(from);
  if (at == std::string::npos || from.size() != to.size()) throw std::runtime_error("cannot patch " + p.string());
  std::memcpy(bytes.data() + at, to.data(), to.size());
  write_bytes(p, bytes);
}

inline std::string new_series_uid() {
  gdcm::UIDGenerator g;
  return g.Generate();
}

// A DICOM file written byte by byte (PS3.10: preamble, "DICM", group 0002 in explicit VR little endian, then the data
// set), so a test can write what GDCM would not: a declared length larger than the file, an unclosed sequence, short
// pixel data, a chosen transfer syntax. Elements are appended in the order given (callers keep tags ascending).
class DicomBytes {
 public:
  enum class Syntax { kExplicitLittle, kImplicitLittle, kExplicitBig };
  explicit DicomBytes(Syntax syntax = Syntax::kExplicitLittle) : syntax_(syntax) {}

  // An element; `length` overrides the value's length in the header (0xFFFFFFFF: undefined). Strings are padded to
  // an even length (UI with a NUL, others with a space).
  DicomBytes& element(std::uint16_t group, std::uint16_t elem, const char* vr, std::vector<unsigned char> value,
                      std::optional<std::uint32_t> length = std::nullopt) {
    header(group, elem, vr, length.value_or(static_cast<std::uint32_t>(value.size())));
    bytes_.insert(bytes_.end(), value.begin(), value.end());
    return *this;
  }
  DicomBytes& text(std::uint16_t group, std::uint16_t elem, const char* vr, std::string value) {
    if (value.size() % 2) value.push_back(std::string(vr) == "UI" ? '\0' : ' ');
    return element(group, elem, vr, {value.begin(), value.end()});
  }
  DicomBytes& us(std::uint16_t group, std::uint16_t elem, std::uint16_t v) {
    return element(
        group, elem, "US",
        big() ? std::vector<unsigned char>{static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v & 0xFF)}
              : std::vector<unsigned char>{static_cast<unsigned char>(v & 0xFF), static_cast<unsigned char>(v >> 8)});
  }
  // An item / delimiter tag (FFFE,eeee) with its 4-byte length.
  DicomBytes& item_tag(std::uint16_t elem, std::uint32_t length) {
    put16(0xFFFE), put16(elem), put32(length);
    return *this;
  }
  DicomBytes& raw(const std::vector<unsigned char>& b) {
    bytes_.insert(bytes_.end(), b.begin(), b.end());
    return *this;
  }
  const std::vector<unsigned char>& data_set() const { return bytes_; }
  std::string transfer_syntax() const {
    return syntax_ == Syntax::kImplicitLittle ? "1.2.840.10008.1.2"
           : syntax_ == Syntax::kExplicitBig  ? "1.2.840.10008.1.2.2"
                                              : "1.2.840.10008.1.2.1";
  }

  // The whole file: preamble, meta header naming `ts` (default: this builder's syntax), the data set as given.
  std::vector<unsigned char> file(const std::string& ts = {},
                                  const std::vector<unsigned char>* data_set = nullptr) const {
    DicomBytes meta;
    meta.element(0x0002, 0x0001, "OB", {0, 1});
    meta.text(0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2");
    meta.text(0x0002, 0x0003, "UI", "1.2.3.4.5");
    meta.text(0x0002, 0x0010, "UI", ts.empty() ? transfer_syntax() : ts);
    DicomBytes group_length;
    const auto n = static_cast<std::uint32_t>(meta.bytes_.size());
    group_length.element(0x0002, 0x0000, "UL",
                         {static_cast<unsigned char>(n), static_cast<unsigned char>(n >> 8),
                          static_cast<unsigned char>(n >> 16), static_cast<unsigned char>(n >> 24)});
    std::vector<unsigned char> out(128, 0);
    for (const char c : std::string("DICM")) out.push_back(static_cast<unsigned char>(c));
    out.insert(out.end(), group_length.bytes_.begin(), group_length.bytes_.end());
    out.insert(out.end(), meta.bytes_.begin(), meta.bytes_.end());
    const std::vector<unsigned char>& ds = data_set ? *data_set : bytes_;
    out.insert(out.end(), ds.begin(), ds.end());
    return out;
  }

 private:
  bool big() const { return syntax_ == Syntax::kExplicitBig; }
  void put16(std::uint16_t v) {
    if (big()) bytes_.push_back(static_cast<unsigned char>(v >> 8));
    bytes_.push_back(static_cast<unsigned char>(v & 0xFF));
    if (!big()) bytes_.push_back(static_cast<unsigned char>(v >> 8));
  }
  void put32(std::uint32_t v) {
    if (big())
      put16(static_cast<std::uint16_t>(v >> 16)), put16(static_cast<std::uint16_t>(v));
    else
      put16(static_cast<std::uint16_t>(v)), put16(static_cast<std::uint16_t>(v >> 16));
  }
  void header(std::uint16_t group, std::uint16_t elem, const char* vr, std::uint32_t length) {
    put16(group), put16(elem);
    if (syntax_ == Syntax::kImplicitLittle && group != 0x0002) return put32(length);
    bytes_.push_back(static_cast<unsigned char>(vr[0]));
    bytes_.push_back(static_cast<unsigned char>(vr[1]));
    const std::string v(vr);
    if (v == "OB" || v == "OW" || v == "OF" || v == "SQ" || v == "UN" || v == "UT" || v == "OD" || v == "OL")
      put16(0), put32(length);
    else
      put16(static_cast<std::uint16_t>(length));
  }
  Syntax syntax_;
  std::vector<unsigned char> bytes_;
};

// The data set elements of one CT slice (rows×cols int16, Image Position (0, 0, z), axial, 1 mm pixels) up to and
// excluding Pixel Data, with `extra` (group 0008 ≥ 0x1000 elements, e.g. a sequence) inserted after the modality.
inline DicomBytes ct_slice_header(DicomBytes::Syntax syntax, const std::string& series_uid, double z, int rows = 3,
                                  int cols = 4, int bits_stored = 16,
                                  const std::function<void(DicomBytes&)>& extra = {}) {
  DicomBytes d(syntax);
  d.text(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
  d.text(0x0008, 0x0018, "UI", series_uid + "." + std::to_string(static_cast<int>(z * 10 + 100)));
  d.text(0x0008, 0x0060, "CS", "CT");
  if (extra) extra(d);
  d.text(0x0020, 0x000D, "UI", series_uid + ".1");
  d.text(0x0020, 0x000E, "UI", series_uid);
  d.text(0x0020, 0x0032, "DS", "0\\0\\" + std::to_string(z));
  d.text(0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0");
  d.us(0x0028, 0x0002, 1);
  d.text(0x0028, 0x0004, "CS", "MONOCHROME2");
  d.us(0x0028, 0x0010, static_cast<std::uint16_t>(rows));
  d.us(0x0028, 0x0011, static_cast<std::uint16_t>(cols));
  d.text(0x0028, 0x0030, "DS", "1\\1");
  d.us(0x0028, 0x0100, 16);
  d.us(0x0028, 0x0101, static_cast<std::uint16_t>(bits_stored));
  d.us(0x0028, 0x0102, static_cast<std::uint16_t>(bits_stored > 0 ? bits_stored - 1 : 0));
  d.us(0x0028, 0x0103, 1);
  return d;
}

// int16 samples as Pixel Data bytes in the builder's byte order.
inline std::vector<unsigned char> pixel_bytes(const std::vector<std::int16_t>& samples, bool big = false) {
  std::vector<unsigned char> b;
  for (const std::int16_t s : samples) {
    const auto u = static_cast<std::uint16_t>(s);
    const unsigned char lo = static_cast<unsigned char>(u & 0xFF), hi = static_cast<unsigned char>(u >> 8);
    if (big)
      b.push_back(hi), b.push_back(lo);
    else
      b.push_back(lo), b.push_back(hi);
  }
  return b;
}

// ---------------------------------------------------------------------------------------------------- InVesalius

// A main.plist as InVesalius writes it (the keys load_volume reads, and a few it does not), with `matrix_dict` and
// `spacing` as given so a test can break them.
inline std::string inv3_plist(const std::string& matrix_dict, const std::string& spacing,
                              const std::string& modality = "CT") {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<!DOCTYPE plist PUBLIC \"-//Apple Computer//DTD PLIST 1.0//EN\" "
         "\"http://www.apple.com/DTDs/PropertyList-1.0.dtd\">\n"
         "<plist version=\"1.0\">\n<dict>\n"
         "\t<key>format_version</key>\n\t<integer>1</integer>\n" +
         matrix_dict + spacing + "\t<key>modality</key>\n\t<string>" + modality +
         "</string>\n"
         "\t<key>window_level</key>\n\t<real>-18.0</real>\n"
         "</dict>\n</plist>\n";
}

inline std::string inv3_matrix_dict(int z, int y, int x, const std::string& dtype = "int16",
                                    const std::string& filename = "matrix.dat") {
  return "\t<key>matrix</key>\n\t<dict>\n\t\t<key>dtype</key>\n\t\t<string>" + dtype +
         "</string>\n\t\t<key>filename</key>\n\t\t<string>" + filename +
         "</string>\n\t\t<key>shape</key>\n\t\t<array>\n\t\t\t<integer>" + std::to_string(z) +
         "</integer>\n\t\t\t<integer>" + std::to_string(y) + "</integer>\n\t\t\t<integer>" + std::to_string(x) +
         "</integer>\n\t\t</array>\n\t</dict>\n";
}

inline std::string inv3_spacing(double x, double y, double z) {
  return "\t<key>spacing</key>\n\t<array>\n\t\t<real>" + std::to_string(x) + "</real>\n\t\t<real>" + std::to_string(y) +
         "</real>\n\t\t<real>" + std::to_string(z) + "</real>\n\t</array>\n";
}

// int16 samples as matrix.dat bytes (little-endian).
inline std::vector<unsigned char> int16_le(const std::vector<std::int16_t>& v) {
  std::vector<unsigned char> b;
  for (const std::int16_t s : v) {
    const auto u = static_cast<std::uint16_t>(s);
    b.push_back(static_cast<unsigned char>(u & 0xFF));
    b.push_back(static_cast<unsigned char>(u >> 8));
  }
  return b;
}

// A tar (gzip'd when `gzip`) of the given entries, in order, through libarchive.
inline void write_tar(const std::filesystem::path& p,
                      const std::vector<std::pair<std::string, std::vector<unsigned char>>>& entries,
                      bool gzip = true) {
  archive* a = archive_write_new();
  if (gzip) archive_write_add_filter_gzip(a);
  archive_write_set_format_pax_restricted(a);
  if (archive_write_open_filename(a, p.c_str()) != ARCHIVE_OK) throw std::runtime_error("cannot write " + p.string());
  for (const auto& [name, bytes] : entries) {
    archive_entry* e = archive_entry_new();
    archive_entry_set_pathname(e, name.c_str());
    archive_entry_set_size(e, static_cast<la_int64_t>(bytes.size()));
    archive_entry_set_filetype(e, AE_IFREG);
    archive_entry_set_perm(e, 0644);
    archive_write_header(a, e);
    if (!bytes.empty()) archive_write_data(a, bytes.data(), bytes.size());
    archive_entry_free(e);
  }
  archive_write_close(a);
  archive_write_free(a);
}

inline std::vector<unsigned char> text_bytes(const std::string& s) { return {s.begin(), s.end()}; }

}  // namespace trispline::test
