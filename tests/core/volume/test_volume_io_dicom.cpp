// load_volume on DICOM series GDCM writes for the test (volume_test_files.h): slice order, orientation, spacing and
// rescale, one file's own series, compressed and deflated slices, and malformed series (slices that disagree,
// undecodable transfer syntaxes, truncated files). Hostile series: test_volume_io_dicom_hostile.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/volume/volume_io.h"
#include "tests/core/volume/volume_test_files.h"

namespace fs = std::filesystem;
using namespace trispline::core;
using namespace trispline::test;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

std::string load_error(const fs::path& p, const VolumeLoadOptions& options = {}) {
  return volume_load_error(p, options);
}

void expect_column(const ScalarVolume& v, int c, glm::dvec3 expected, double tolerance = 1e-6) {
  for (int r = 0; r < 3; ++r)
    EXPECT_NEAR(v.index_to_world[c][r], expected[r], tolerance) << "index_to_world column " << c << " row " << r;
  EXPECT_EQ(v.index_to_world[c][3], c == 3 ? 1.0 : 0.0);
}

}  // namespace

namespace {

// n slices of `base` at base.position + k·gap·normal, raw sample (i, j, k) = i + 10 j + 100 k, written under
// `prefix` with names in a different order than their positions (k = n−1 first).
void write_series(const TempFolder& dir, const std::string& prefix, DicomSlice base, int n, double gap) {
  const glm::dvec3 row(base.orientation[0], base.orientation[1], base.orientation[2]);
  const glm::dvec3 col(base.orientation[3], base.orientation[4], base.orientation[5]);
  const glm::dvec3 normal = glm::cross(row, col);
  const glm::dvec3 origin = base.position;
  for (int k = 0; k < n; ++k) {
    DicomSlice s = base;
    s.position = origin + normal * (gap * k);
    s.instance = k + 1;
    s.pixels.clear();
    for (int j = 0; j < s.rows; ++j)
      for (int i = 0; i < s.cols; ++i) s.pixels.push_back(static_cast<std::int16_t>(i + 10 * j + 100 * k));
    write_dicom_slice(dir / (prefix + std::to_string(n - 1 - k) + ".dcm"), s);
  }
}

DicomSlice sagittal_ct() {
  DicomSlice s;
  s.series_uid = new_series_uid();
  s.orientation = {0, 1, 0, 0, 0, -1};  // rows along +y, columns along −z: normal (−1, 0, 0)
  s.position = {10, -20, 30};
  s.spacing_x = 0.5;
  s.spacing_y = 0.7;
  s.slope = 2.0;
  s.intercept = -1024.0;
  return s;
}

}  // namespace

TEST(DicomSeries, FolderSortedByPositionWithOrientationSpacingAndRescale) {
  TempFolder dir;
  write_series(dir, "IM", sagittal_ct(), 5, 2.5);
  const ScalarVolume v = load_volume(dir.path());
  EXPECT_EQ(v.dims, (std::array<int, 3>{4, 3, 5}));
  expect_column(v, 0, {0, 0.5, 0});    // row direction × the spacing between columns
  expect_column(v, 1, {0, 0, -0.7});   // column direction × the spacing between rows
  expect_column(v, 2, {-2.5, 0, 0});   // the normal × the slice gap
  expect_column(v, 3, {10, -20, 30});  // the first slice's Image Position
  EXPECT_EQ(v.modality, "CT");
  EXPECT_EQ(v.units, "HU");
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) ASSERT_EQ(v.at(i, j, k), (i + 10 * j + 100 * k) * 2.0f - 1024.0f) << i << j << k;
  const glm::dvec3 last = v.world({0, 0, 4});
  EXPECT_NEAR(last.x, 0.0, 1e-9);
  EXPECT_NEAR(last.y, -20.0, 1e-9);
}

TEST(DicomSeries, OneDcmFileLoadsItsOwnSeries) {
  TempFolder dir;
  DicomSlice a = sagittal_ct(), b = sagittal_ct();
  b.series_uid = new_series_uid();
  b.orientation = {1, 0, 0, 0, 1, 0};
  write_series(dir, "a", a, 3, 1.0);
  write_series(dir, "b", b, 4, 1.5);
  const ScalarVolume va = load_volume(dir / "a1.dcm");
  EXPECT_EQ(va.dims[2], 3);
  expect_column(va, 2, {-1, 0, 0});
  const ScalarVolume vb = load_volume(dir / "b0.dcm");
  EXPECT_EQ(vb.dims[2], 4);
  expect_column(vb, 2, {0, 0, 1.5});
  // The folder itself holds two series: refused, both listed.
  const std::string why = load_error(dir.path());
  EXPECT_THAT(why, AllOf(HasSubstr("2 DICOM series"), HasSubstr(a.series_uid), HasSubstr(b.series_uid),
                         HasSubstr("3 images"), HasSubstr("4 images")));
}

TEST(DicomSeries, EachSliceItsOwnRescale) {
  TempFolder dir;
  const DicomSlice s = sagittal_ct();
  for (int k = 0; k < 3; ++k) {  // the geometry of write_series, intercept 1000 k and slope 1 per slice
    DicomSlice t = s;
    t.position = s.position + glm::dvec3(-1, 0, 0) * double(k);
    t.slope = 1.0;
    t.intercept = 1000.0 * k;
    t.pixels.assign(12, static_cast<std::int16_t>(5));
    write_dicom_slice(dir / ("ct" + std::to_string(k) + ".dcm"), t);
  }
  const ScalarVolume v = load_volume(dir.path());
  EXPECT_EQ(v.at(0, 0, 0), 5.0f);
  EXPECT_EQ(v.at(3, 2, 1), 1005.0f);
  EXPECT_EQ(v.at(1, 1, 2), 2005.0f);
}

// 12 bits stored of 16: the bits above are not part of the value (old scanners put overlays there).
TEST(DicomSeries, BitsAboveBitsStoredAreDropped) {
  for (const bool is_signed : {false, true}) {
    TempFolder dir;
    DicomSlice s = sagittal_ct();
    s.slope = 1.0;
    s.intercept = 0.0;
    s.bits_stored = 12;
    s.is_signed = is_signed;
    for (int k = 0; k < 2; ++k) {
      DicomSlice t = s;
      t.position = s.position + glm::dvec3(-1, 0, 0) * double(k);
      // 0xF123: overlay bits F over 0x123; 0x0FFF: −1 in 12-bit two's complement, 4095 unsigned.
      t.pixels = {static_cast<std::int16_t>(0xF123), 0x0FFF, 0x0800, 5, 6, 7, 8, 9, 10, 11, 12, 13};
      write_dicom_slice(dir / ("b" + std::to_string(k) + ".dcm"), t);
    }
    const ScalarVolume v = load_volume(dir.path());
    EXPECT_EQ(v.at(0, 0, 0), 0x123) << is_signed;
    EXPECT_EQ(v.at(1, 0, 1), is_signed ? -1.0f : 4095.0f);
    EXPECT_EQ(v.at(2, 0, 0), is_signed ? -2048.0f : 2048.0f);
    EXPECT_EQ(v.at(3, 2, 1), 13.0f);
  }
}

TEST(DicomSeries, MrHasNoValueUnits) {
  TempFolder dir;
  DicomSlice s = sagittal_ct();
  s.modality = "MR";
  s.slope = 1.0;
  s.intercept = 0.0;
  write_series(dir, "mr", s, 3, 1.0);
  const ScalarVolume v = load_volume(dir.path());
  EXPECT_EQ(v.modality, "MR");
  EXPECT_EQ(v.units, "");
  EXPECT_EQ(v.at(3, 2, 1), 123.0f);
}

TEST(DicomMalformed, EnhancedImagesAreRefused) {
  TempFolder dir;
  DicomSlice s = sagittal_ct();
  s.modality = "MR";  // with a rescale GDCM writes Enhanced MR Image Storage (functional groups)
  write_series(dir, "emr", s, 3, 1.0);
  EXPECT_THAT(load_error(dir.path()), HasSubstr("enhanced images are not read"));
}

TEST(DicomSeries, CompressedSlicesDecode) {
  for (const auto ts : {gdcm::TransferSyntax::JPEGLosslessProcess14_1, gdcm::TransferSyntax::JPEGLSLossless,
                        gdcm::TransferSyntax::JPEG2000Lossless, gdcm::TransferSyntax::RLELossless}) {
    TempFolder dir;
    DicomSlice s = sagittal_ct();
    s.rows = s.cols = 64;
    write_series(dir, "c", s, 3, 2.0);
    for (int k = 0; k < 3; ++k) recode_dicom(dir / ("c" + std::to_string(k) + ".dcm"), ts);
    const std::vector<unsigned char> bytes = read_bytes(dir / "c0.dcm");
    ASSERT_NE(std::string(bytes.begin(), bytes.end()).find(gdcm::TransferSyntax::GetTSString(ts)), std::string::npos);
    const ScalarVolume v = load_volume(dir.path());
    ASSERT_EQ(v.dims, (std::array<int, 3>{64, 64, 3})) << gdcm::TransferSyntax::GetTSString(ts);
    std::size_t differ = 0;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) differ += v.at(i, j, k) != (i + 10 * j + 100 * k) * 2.0f - 1024.0f;
    EXPECT_EQ(differ, 0u) << gdcm::TransferSyntax::GetTSString(ts);
  }
}

// A deflated data set: GDCM's stream positions there are not file offsets (the truncation check stands aside).
TEST(DicomSeries, DeflatedDataSetLoads) {
  TempFolder dir;
  write_series(dir, "d", sagittal_ct(), 3, 2.0);
  for (int k = 0; k < 3; ++k) deflate_dicom(dir / ("d" + std::to_string(k) + ".dcm"));
  const std::vector<unsigned char> bytes = read_bytes(dir / "d0.dcm");
  ASSERT_NE(std::string(bytes.begin(), bytes.end()).find("1.2.840.10008.1.2.1.99"), std::string::npos);
  const ScalarVolume v = load_volume(dir.path());
  EXPECT_EQ(v.at(3, 2, 2), (3 + 20 + 200) * 2.0f - 1024.0f);
}

TEST(DicomMalformed, UndecodableTransferSyntax) {
  TempFolder dir;
  DicomSlice s = sagittal_ct();
  s.rows = s.cols = 64;
  write_series(dir, "c", s, 3, 2.0);
  for (int k = 0; k < 3; ++k)
    recode_dicom(dir / ("c" + std::to_string(k) + ".dcm"), gdcm::TransferSyntax::JPEGLosslessProcess14_1);
  // JPIP Referenced: the pixels live on a server; GDCM has nothing to decode.
  patch_file_text(dir / "c1.dcm", "1.2.840.10008.1.2.4.70", "1.2.840.10008.1.2.4.94");
  EXPECT_THAT(load_error(dir.path()),
              AllOf(HasSubstr("c1.dcm"), HasSubstr("cannot decode"), HasSubstr("1.2.840.10008.1.2.4.94")));
}

TEST(DicomMalformed, InconsistentSpacingOrDuplicatePositions) {
  const DicomSlice base = sagittal_ct();
  for (const auto& [offsets, reason] : {std::pair{std::vector<double>{0, 2, 4, 7}, "not uniform"},
                                        std::pair{std::vector<double>{0, 2, 2, 4}, "two slices at one position"},
                                        std::pair{std::vector<double>{3, 3, 3, 3}, "at one position"}}) {
    TempFolder dir;
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      DicomSlice s = base;
      s.position = base.position + glm::dvec3(-offsets[k], 0, 0);
      s.pixels.assign(12, 1);
      write_dicom_slice(dir / ("s" + std::to_string(k) + ".dcm"), s);
    }
    EXPECT_THAT(load_error(dir.path()), HasSubstr(reason));
  }
}

TEST(DicomMalformed, SlicesThatDisagree) {
  const DicomSlice base = sagittal_ct();
  {
    TempFolder dir;
    write_series(dir, "s", base, 3, 1.0);
    DicomSlice odd = base;
    odd.orientation = {1, 0, 0, 0, 1, 0};
    odd.position = base.position + glm::dvec3(-3, 0, 0);
    odd.pixels.assign(12, 1);
    write_dicom_slice(dir / "s9.dcm", odd);
    EXPECT_THAT(load_error(dir.path()), HasSubstr("Image Orientation (Patient)"));
  }
  {
    TempFolder dir;
    write_series(dir, "s", base, 3, 1.0);
    DicomSlice big = base;
    big.rows = 5;
    big.position = base.position + glm::dvec3(-3, 0, 0);
    big.pixels.assign(20, 1);
    write_dicom_slice(dir / "s9.dcm", big);
    EXPECT_THAT(load_error(dir.path()), HasSubstr("one slice size"));
  }
  {
    TempFolder dir;
    write_series(dir, "s", base, 3, 1.0);
    DicomSlice wide = base;
    wide.spacing_x = 0.9;
    wide.position = base.position + glm::dvec3(-3, 0, 0);
    wide.pixels.assign(12, 1);
    write_dicom_slice(dir / "s9.dcm", wide);
    EXPECT_THAT(load_error(dir.path()), HasSubstr("Pixel Spacing"));
  }
}

TEST(DicomMalformed, EmptyGarbageOrSingleSlice) {
  {
    TempFolder dir;
    EXPECT_THAT(load_error(dir.path()), HasSubstr("no DICOM images in the folder (0 files"));
  }
  {
    TempFolder dir;
    write_bytes(dir / "notes.txt", text_bytes("not an image\n"));
    write_bytes(dir / "noise.dcm", std::vector<unsigned char>(3000, 0xA5));
    EXPECT_THAT(load_error(dir.path()), HasSubstr("no DICOM images in the folder (2 files"));
    EXPECT_THAT(load_error(dir / "noise.dcm"), HasSubstr("not a DICOM file"));
  }
  {
    TempFolder dir;
    write_series(dir, "one", sagittal_ct(), 1, 1.0);
    EXPECT_THAT(load_error(dir.path()), HasSubstr("at least 2"));
  }
}

TEST(DicomMalformed, TruncatedSliceFile) {
  TempFolder dir;
  write_series(dir, "s", sagittal_ct(), 3, 1.0);
  std::vector<unsigned char> bytes = read_bytes(dir / "s1.dcm");
  bytes.resize(bytes.size() - 11);  // into the pixel data: GDCM alone would fill the rest with zeros
  write_bytes(dir / "s1.dcm", bytes);
  EXPECT_THAT(load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("truncated")));
  bytes.resize(bytes.size() - 30);  // into the pixel data's header
  write_bytes(dir / "s1.dcm", bytes);
  EXPECT_THAT(load_error(dir.path()), HasSubstr("s1.dcm"));
}
