// Volume files the loader test writes itself: NIfTI through niftilib, DICOM slices through GDCM, InVesalius .inv3
// projects (tar / tar.gz through libarchive, main.plist as text), and a temporary folder per test.
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
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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
