// load_volume on real files (assets/data: InVesalius' Cranium.inv3, ITK's T1 brain NIfTI), on NIfTI, DICOM and
// .inv3 files the test writes itself (niftilib, GDCM, libarchive; volume_test_files.h), and on malformed ones: every
// refusal is a VolumeLoadError naming the file and the reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/volume/volume_io.h"
#include "core/volume/volume_io_formats.h"
#include "tests/core/volume/volume_test_files.h"

namespace fs = std::filesystem;
using namespace trispline::core;
using namespace trispline::test;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

fs::path asset(const std::string& name) { return fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "data" / name; }

// The message of the VolumeLoadError load_volume throws (a test failure if it loads or throws something else).
std::string load_error(const fs::path& p, const VolumeLoadOptions& options = {}) {
  try {
    const ScalarVolume v = load_volume(p, options);
    ADD_FAILURE() << p << " loaded as " << v.dims[0] << "×" << v.dims[1] << "×" << v.dims[2];
  } catch (const VolumeLoadError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr(p.filename().string())) << "the message must name the file";
    return what;
  }
  return {};
}

void expect_column(const ScalarVolume& v, int c, glm::dvec3 expected, double tolerance = 1e-6) {
  for (int r = 0; r < 3; ++r)
    EXPECT_NEAR(v.index_to_world[c][r], expected[r], tolerance) << "index_to_world column " << c << " row " << r;
  EXPECT_EQ(v.index_to_world[c][3], c == 3 ? 1.0 : 0.0);
}

std::vector<std::int16_t> ramp_int16(int nx, int ny, int nz) {  // sample (i, j, k) = i + 10 j + 100 k
  std::vector<std::int16_t> s;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) s.push_back(static_cast<std::int16_t>(i + 10 * j + 100 * k));
  return s;
}

// A valid 8×8×8 int16 .nii to break.
fs::path small_nifti(const TempFolder& dir, const std::string& name = "small.nii") {
  const fs::path p = dir / name;
  write_nifti(p, {8, 8, 8}, DT_INT16, as_bytes(ramp_int16(8, 8, 8)));
  return p;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------ dispatch

TEST(VolumePaths, ExtensionsAndFolders) {
  TempFolder dir;
  EXPECT_TRUE(is_volume_path("a/b.nii"));
  EXPECT_TRUE(is_volume_path("b.NII.GZ"));
  EXPECT_TRUE(is_volume_path("project.Inv3"));
  EXPECT_TRUE(is_volume_path("IM0001.DCM"));
  EXPECT_TRUE(is_volume_path(dir.path()));
  EXPECT_FALSE(is_volume_path("mesh.obj"));
  EXPECT_FALSE(is_volume_path("archive.gz"));
  EXPECT_FALSE(is_volume_path("nii"));
  EXPECT_FALSE(is_volume_path(dir / "no_such_folder"));
}

TEST(VolumePaths, MissingOrUnknownFilesAreRefused) {
  TempFolder dir;
  EXPECT_THAT(load_error(dir / "absent.nii"), HasSubstr("no such file"));
  write_bytes(dir / "mesh.obj", text_bytes("v 0 0 0\n"));
  EXPECT_THAT(load_error(dir / "mesh.obj"), HasSubstr("not a volume file"));
}

// --------------------------------------------------------------------------------------------------------- NIfTI

// ITK's T1 MRI brain (insighttoolkit5-examples): int16 samples 0…255 despite its name, sform coronal 2×2×3 mm.
TEST(NiftiFiles, RealT1BrainFromItk) {
  const fs::path p = asset("KmeansTest_T1UCharRaw.nii.gz");
  ASSERT_TRUE(fs::exists(p)) << p << " missing: run scripts/fetch_assets.sh";
  const ScalarVolume v = load_volume(p);
  EXPECT_EQ(v.dims, (std::array<int, 3>{128, 128, 62}));
  EXPECT_EQ(v.source, p.string());
  EXPECT_EQ(v.units, "");
  expect_column(v, 0, {-2, 0, 0});  // the file's sform rows: (-2 0 0 0), (0 0 3 -254), (0 2 0 0)
  expect_column(v, 1, {0, 0, 2});
  expect_column(v, 2, {0, 3, 0});
  expect_column(v, 3, {0, -254, 0});
  double sum = 0, lo = 1e9, hi = -1e9;
  for (const float s : v.values) sum += s, lo = std::min<double>(lo, s), hi = std::max<double>(hi, s);
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 255.0);
  EXPECT_EQ(sum, 19533798.0);
  EXPECT_EQ(v.at(64, 64, 31), 97.0f);

  // Sample for sample what niftilib's own reader returns (int16: nothing for it to "fix").
  nifti_image* nim = nifti_image_read(p.c_str(), 1);
  ASSERT_NE(nim, nullptr);
  ASSERT_EQ(nim->datatype, DT_INT16);
  ASSERT_EQ(nim->nvox, v.values.size());
  const auto* lib = static_cast<const std::int16_t*>(nim->data);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < v.values.size(); ++i) differ += v.values[i] != static_cast<float>(lib[i]);
  nifti_image_free(nim);
  EXPECT_EQ(differ, 0u);
}

TEST(NiftiFiles, SformWinsOverQform) {
  TempFolder dir;
  const fs::path p = dir / "both.nii";
  write_nifti(p, {3, 4, 5}, DT_INT16, as_bytes(ramp_int16(3, 4, 5)), [](nifti_image& nim) {
    set_qform(nim, make_mat44({{{1, 0, 0, 100}, {0, 1, 0, 100}, {0, 0, 1, 100}}}));
    nim.sform_code = NIFTI_XFORM_MNI_152;
    nim.sto_xyz = make_mat44({{{0.5f, 0.1f, 0, -10}, {0, 0.6f, 0, -20}, {0, 0, 1.5f, -30}}});
  });
  const ScalarVolume v = load_volume(p);
  expect_column(v, 0, {0.5, 0, 0});
  expect_column(v, 1, {0.1, 0.6, 0});
  expect_column(v, 2, {0, 0, 1.5});
  expect_column(v, 3, {-10, -20, -30});
  EXPECT_EQ(v.at(2, 3, 4), 432.0f);
}

TEST(NiftiFiles, QformWhenThereIsNoSform) {
  TempFolder dir;
  const fs::path p = dir / "qform.nii";
  // 90° about z, pixdim 2 × 3 × 4, a reflection (qfac −1) flipping k.
  write_nifti(p, {3, 4, 5}, DT_INT16, as_bytes(ramp_int16(3, 4, 5)), [](nifti_image& nim) {
    set_qform(nim, make_mat44({{{0, -3, 0, 10}, {2, 0, 0, 20}, {0, 0, -4, 30}}}));
  });
  ASSERT_EQ(read_nifti_header(p).sform_code, 0);
  ASSERT_GT(read_nifti_header(p).qform_code, 0);
  ASSERT_EQ(read_nifti_header(p).pixdim[0], -1.0f);  // qfac
  const ScalarVolume v = load_volume(p);
  expect_column(v, 0, {0, 2, 0}, 1e-5);
  expect_column(v, 1, {-3, 0, 0}, 1e-5);
  expect_column(v, 2, {0, 0, -4}, 1e-5);
  expect_column(v, 3, {10, 20, 30}, 1e-5);
}

TEST(NiftiFiles, PixdimWhenThereIsNeitherForm) {
  TempFolder dir;
  const fs::path p = dir / "pixdim.nii";
  write_nifti(p, {3, 4, 5}, DT_INT16, as_bytes(ramp_int16(3, 4, 5)), [](nifti_image& nim) {
    nim.dx = nim.pixdim[1] = 0.5f;
    nim.dy = nim.pixdim[2] = 0.75f;
    nim.dz = nim.pixdim[3] = 2.0f;
  });
  const ScalarVolume v = load_volume(p);
  expect_column(v, 0, {0.5, 0, 0});
  expect_column(v, 1, {0, 0.75, 0});
  expect_column(v, 2, {0, 0, 2});
  expect_column(v, 3, {0, 0, 0});
}

TEST(NiftiFiles, SpatialUnitsBecomeMillimetres) {
  TempFolder dir;
  for (const auto& [unit, mm] : {std::pair{NIFTI_UNITS_METER, 1000.0}, std::pair{NIFTI_UNITS_MICRON, 0.001},
                                 std::pair{NIFTI_UNITS_MM, 1.0}, std::pair{NIFTI_UNITS_UNKNOWN, 1.0}}) {
    const fs::path p = dir / ("units" + std::to_string(unit) + ".nii");
    write_nifti(p, {2, 2, 2}, DT_UINT8, std::vector<unsigned char>(8, 7), [unit = unit](nifti_image& nim) {
      nim.xyz_units = unit;
      nim.sform_code = NIFTI_XFORM_SCANNER_ANAT;
      nim.sto_xyz = make_mat44({{{2, 0, 0, 1}, {0, 2, 0, 0}, {0, 0, 2, 0}}});
    });
    const ScalarVolume v = load_volume(p);
    expect_column(v, 0, {2 * mm, 0, 0}, 1e-9 * mm + 1e-12);
    expect_column(v, 3, {mm, 0, 0}, 1e-9 * mm + 1e-12);
  }
}

TEST(NiftiFiles, SclSlopeAndInterceptAreApplied) {
  TempFolder dir;
  const fs::path scaled = dir / "scaled.nii", raw = dir / "raw.nii";
  const std::vector<std::int16_t> s = ramp_int16(3, 4, 5);
  write_nifti(scaled, {3, 4, 5}, DT_INT16, as_bytes(s), [](nifti_image& nim) {
    nim.scl_slope = 2.0f;
    nim.scl_inter = -1024.0f;
  });
  write_nifti(raw, {3, 4, 5}, DT_INT16, as_bytes(s), [](nifti_image& nim) {
    nim.scl_slope = 0.0f;  // "no scaling", whatever the intercept
    nim.scl_inter = 55.0f;
  });
  const ScalarVolume a = load_volume(scaled), b = load_volume(raw);
  for (std::size_t i = 0; i < s.size(); ++i) {
    ASSERT_EQ(a.values[i], s[i] * 2.0f - 1024.0f) << i;
    ASSERT_EQ(b.values[i], static_cast<float>(s[i])) << i;
  }
}

template <typename T>
void expect_datatype_round_trip(const TempFolder& dir, int datatype) {
  const std::vector<T> s = {
      std::numeric_limits<T>::lowest(), std::numeric_limits<T>::max(), T(0), T(1), T(2), T(3), T(100), T(7)};
  const fs::path p = dir / ("type" + std::to_string(datatype) + ".nii");
  write_nifti(p, {2, 2, 2}, datatype, as_bytes(s));
  const ScalarVolume v = load_volume(p);
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_EQ(v.values[i], static_cast<float>(s[i])) << nifti_datatype_string(datatype) << " sample " << i;
}

TEST(NiftiFiles, EverySupportedDatatypeBecomesFloat) {
  TempFolder dir;
  expect_datatype_round_trip<std::uint8_t>(dir, DT_UINT8);
  expect_datatype_round_trip<std::int8_t>(dir, DT_INT8);
  expect_datatype_round_trip<std::int16_t>(dir, DT_INT16);
  expect_datatype_round_trip<std::uint16_t>(dir, DT_UINT16);
  expect_datatype_round_trip<std::int32_t>(dir, DT_INT32);
  expect_datatype_round_trip<std::uint32_t>(dir, DT_UINT32);
  expect_datatype_round_trip<float>(dir, DT_FLOAT32);
  // float64 within float's range (its extremes would overflow float and are refused: see NonFiniteSamplesAreRefused)
  const std::vector<double> d = {-1e30, 1e30, 0.0, 0.25, -3.5, 1e-3, 65504.0, 7.0};
  write_nifti(dir / "f64.nii", {2, 2, 2}, DT_FLOAT64, as_bytes(d));
  const ScalarVolume v = load_volume(dir / "f64.nii");
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(v.values[i], static_cast<float>(d[i])) << i;
}

TEST(NiftiFiles, GzipFloat32) {
  TempFolder dir;
  const fs::path p = dir / "float.nii.gz";
  std::vector<float> s(5 * 6 * 7);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = std::sin(static_cast<float>(i)) * 1000.0f;
  write_nifti(p, {5, 6, 7}, DT_FLOAT32, as_bytes(s), [](nifti_image& nim) {
    nim.sform_code = NIFTI_XFORM_ALIGNED_ANAT;
    nim.sto_xyz = make_mat44({{{0.9f, 0, 0, 1}, {0, 0.9f, 0, 2}, {0, 0, 1.2f, 3}}});
  });
  ASSERT_NE(read_bytes(p)[0], 0x5c) << "expected a gzip stream, not a raw header";
  const ScalarVolume v = load_volume(p);
  EXPECT_EQ(v.dims, (std::array<int, 3>{5, 6, 7}));
  EXPECT_EQ(v.values, s);
  expect_column(v, 2, {0, 0, 1.2}, 1e-6);
}

TEST(NiftiFiles, BigEndianFileReadsLikeLittleEndian) {
  TempFolder dir;
  const fs::path little = small_nifti(dir, "little.nii"), big = dir / "big.nii";
  std::vector<unsigned char> bytes = read_bytes(little);
  nifti_1_header h;
  std::memcpy(&h, bytes.data(), sizeof h);
  const std::size_t offset = static_cast<std::size_t>(h.vox_offset);
  swap_nifti_header(&h, 1);
  std::memcpy(bytes.data(), &h, sizeof h);
  nifti_swap_Nbytes((bytes.size() - offset) / 2, 2, bytes.data() + offset);
  write_bytes(big, bytes);
  const ScalarVolume a = load_volume(little), b = load_volume(big);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.index_to_world, b.index_to_world);
}

TEST(NiftiMalformed, TruncatedSamples) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  std::vector<unsigned char> bytes = read_bytes(p);
  bytes.resize(bytes.size() - 10);
  write_bytes(p, bytes);
  EXPECT_THAT(load_error(p), HasSubstr("truncated"));
}

TEST(NiftiMalformed, TruncatedGzipStream) {
  TempFolder dir;
  const fs::path p = dir / "cut.nii.gz";
  std::vector<float> s(16 * 16 * 16);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = std::sin(static_cast<float>(i) * 0.37f);  // poorly compressible
  write_nifti(p, {16, 16, 16}, DT_FLOAT32, as_bytes(s));
  std::vector<unsigned char> bytes = read_bytes(p);
  bytes.resize(bytes.size() * 6 / 10);
  write_bytes(p, bytes);
  EXPECT_THAT(load_error(p), HasSubstr("truncated"));
}

TEST(NiftiMalformed, ShortOrEmptyHeader) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  std::vector<unsigned char> bytes = read_bytes(p);
  bytes.resize(100);
  write_bytes(dir / "short.nii", bytes);
  EXPECT_THAT(load_error(dir / "short.nii"), HasSubstr("truncated"));
  write_bytes(dir / "empty.nii", nullptr, 0);
  EXPECT_THAT(load_error(dir / "empty.nii"), HasSubstr("truncated"));
}

TEST(NiftiMalformed, DimensionsOtherThanOneVolume) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  const auto with = [&](auto edit) {
    write_bytes(p, good);
    patch_nifti_header(p, edit);
    return load_error(p);
  };
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[3] = 0; }), HasSubstr("at least 2 per axis"));
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[1] = 1; }), HasSubstr("at least 2 per axis"));
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[2] = -8; }), HasSubstr("at least 2 per axis"));
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[0] = 2; }), HasSubstr("dim[0] is 2"));
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[0] = 9; }), HasSubstr("dim[0] is 9"));
  EXPECT_THAT(with([](nifti_1_header& h) { h.dim[0] = 4, h.dim[4] = 3; }), HasSubstr("time series"));
  // dim[0] 4 or 5 with the extra dimensions 1 is one volume.
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) { h.dim[0] = 5, h.dim[4] = 1, h.dim[5] = 1; });
  EXPECT_EQ(load_volume(p).dims, (std::array<int, 3>{8, 8, 8}));
}

// A header claiming more samples than the budget fails on the header alone; one within a huge budget fails on the
// file size — both before the samples are allocated (allocating 100 TB would end in "out of memory").
TEST(NiftiMalformed, HugeDimensionsFailBeforeAllocating) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  patch_nifti_header(p, [](nifti_1_header& h) { h.dim[1] = h.dim[2] = h.dim[3] = 30000; });
  EXPECT_THAT(load_error(p), HasSubstr("over the memory budget of 4.0 GiB"));
  VolumeLoadOptions huge;
  huge.memory_budget_bytes = std::uint64_t{1} << 62;
  const std::string why = load_error(p, huge);
  EXPECT_THAT(why, HasSubstr("truncated"));
  EXPECT_THAT(why, ::testing::Not(HasSubstr("out of memory")));
  // And a valid file over a small budget.
  VolumeLoadOptions small;
  small.memory_budget_bytes = 1024;
  EXPECT_THAT(load_error(small_nifti(dir, "valid.nii"), small), HasSubstr("over the memory budget of 1.0 KiB"));
}

TEST(NiftiMalformed, NonFiniteSamplesAreRefused) {
  TempFolder dir;
  std::vector<float> s(8, 1.0f);
  s[5] = std::numeric_limits<float>::quiet_NaN();
  write_nifti(dir / "nan.nii", {2, 2, 2}, DT_FLOAT32, as_bytes(s));
  EXPECT_THAT(load_error(dir / "nan.nii"), HasSubstr("sample 5 is not a finite number"));
  s[5] = 1.0f;
  s[2] = -std::numeric_limits<float>::infinity();
  write_nifti(dir / "inf.nii.gz", {2, 2, 2}, DT_FLOAT32, as_bytes(s));
  EXPECT_THAT(load_error(dir / "inf.nii.gz"), HasSubstr("sample 2 is not a finite number"));
  const std::vector<double> d = {1, 2, 3, 1e300, 5, 6, 7, 8};  // beyond float
  write_nifti(dir / "big.nii", {2, 2, 2}, DT_FLOAT64, as_bytes(d));
  EXPECT_THAT(load_error(dir / "big.nii"), HasSubstr("sample 3 is not a finite number"));
  write_nifti(dir / "slope.nii", {2, 2, 2}, DT_INT16, as_bytes(std::vector<std::int16_t>(8, 1000)),
              [](nifti_image& nim) { nim.scl_slope = 1e37f; });  // 1000 · 1e37 overflows float
  EXPECT_THAT(load_error(dir / "slope.nii"), HasSubstr("sample 0 is not a finite number"));
}

TEST(NiftiMalformed, WrongVoxOffset) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  const auto with = [&](float offset) {
    write_bytes(p, good);
    patch_nifti_header(p, [offset](nifti_1_header& h) { h.vox_offset = offset; });
    return load_error(p);
  };
  EXPECT_THAT(with(100.0f), HasSubstr("vox_offset"));
  EXPECT_THAT(with(352.5f), HasSubstr("vox_offset"));
  EXPECT_THAT(with(std::numeric_limits<float>::quiet_NaN()), HasSubstr("vox_offset"));
  EXPECT_THAT(with(1e12f), HasSubstr("vox_offset"));
  EXPECT_THAT(with(1e6f), HasSubstr("past the end of the file"));
  EXPECT_THAT(with(static_cast<float>(good.size() - 100)), HasSubstr("truncated"));  // samples run past the end
}

TEST(NiftiMalformed, UnsupportedDatatypes) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  for (const auto& [type, bits] : {std::pair{DT_COMPLEX64, 64}, std::pair{DT_RGB24, 24}, std::pair{DT_INT64, 64},
                                   std::pair{DT_FLOAT128, 128}, std::pair{DT_BINARY, 1}, std::pair{12345, 16}}) {
    write_bytes(p, good);
    patch_nifti_header(p, [type = type, bits = bits](nifti_1_header& h) {
      h.datatype = static_cast<short>(type);
      h.bitpix = static_cast<short>(bits);
    });
    EXPECT_THAT(load_error(p), HasSubstr("is not supported")) << type;
  }
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) { h.bitpix = 8; });  // int16 with bitpix 8
  EXPECT_THAT(load_error(p), HasSubstr("bitpix is 8"));
}

TEST(NiftiMalformed, NotANiftiOneFile) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  patch_nifti_header(p, [](nifti_1_header& h) { std::memcpy(h.magic, "ni1", 4); });
  EXPECT_THAT(load_error(p), HasSubstr("two-file NIfTI pair"));
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) { std::memcpy(h.magic, "\0\0\0", 4); });
  EXPECT_THAT(load_error(p), HasSubstr("not a NIfTI-1 file"));
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) { h.sizeof_hdr = 540; });
  EXPECT_THAT(load_error(p), HasSubstr("NIfTI-2"));
  std::vector<unsigned char> garbage(4096);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<unsigned char>(i * 2654435761u >> 13);
  write_bytes(dir / "garbage.nii", garbage);
  EXPECT_THAT(load_error(dir / "garbage.nii"), HasSubstr("not a NIfTI-1 file"));
  write_bytes(dir / "garbage.nii.gz", garbage);  // not gzip: zlib reads it as plain bytes, still no header
  EXPECT_THAT(load_error(dir / "garbage.nii.gz"), HasSubstr("not a NIfTI-1 file"));
}

TEST(NiftiMalformed, NonFiniteOrSingularGeometry) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  patch_nifti_header(p, [](nifti_1_header& h) { h.scl_slope = std::numeric_limits<float>::quiet_NaN(); });
  EXPECT_THAT(load_error(p), HasSubstr("scl_slope"));
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) {
    h.sform_code = 1;
    h.srow_x[0] = h.srow_y[1] = h.srow_z[2] = 1.0f;
    h.srow_y[3] = std::numeric_limits<float>::infinity();
  });
  EXPECT_THAT(load_error(p), HasSubstr("not finite"));
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) {
    h.sform_code = 1;
    for (int c = 0; c < 4; ++c) h.srow_x[c] = h.srow_y[c] = h.srow_z[c] = 0.0f;
  });
  EXPECT_THAT(load_error(p), HasSubstr("singular"));
}

// --------------------------------------------------------------------------------------------------------- DICOM

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

// ------------------------------------------------------------------------------------------------- InVesalius .inv3

// InVesalius' example project (invesalius-examples): a CT skull. The plist's scalar_range says −1024…3033; the
// matrix itself holds −1024…2986.
TEST(Inv3Files, RealCranium) {
  const fs::path p = asset("Cranium.inv3");
  ASSERT_TRUE(fs::exists(p)) << p << " missing: run scripts/fetch_assets.sh";
  const ScalarVolume v = load_volume(p);
  EXPECT_EQ(v.dims, (std::array<int, 3>{256, 256, 108}));
  expect_column(v, 0, {0.9570312, 0, 0}, 1e-9);
  expect_column(v, 1, {0, 0.9570312, 0}, 1e-9);
  expect_column(v, 2, {0, 0, 1.5});
  expect_column(v, 3, {0, 0, 0});
  EXPECT_EQ(v.units, "HU");
  EXPECT_EQ(v.modality, "CT");
  double sum = 0, lo = 1e9, hi = -1e9;
  for (const float s : v.values) sum += s, lo = std::min<double>(lo, s), hi = std::max<double>(hi, s);
  EXPECT_EQ(lo, -1024.0);
  EXPECT_EQ(hi, 2986.0);
  EXPECT_EQ(sum, -4147325847.0);
  EXPECT_EQ(v.at(0, 0, 0), -998.0f);
  EXPECT_EQ(v.at(128, 128, 54), 3.0f);
  EXPECT_EQ(v.at(100, 150, 20), 55.0f);
}

namespace {

const std::string kGoodPlist = inv3_plist(inv3_matrix_dict(2, 3, 4), inv3_spacing(0.5, 0.625, 1.25));

void write_project(const fs::path& p, const std::string& plist, const std::vector<unsigned char>& matrix,
                   bool matrix_first = false, bool gzip = true) {
  std::vector<std::pair<std::string, std::vector<unsigned char>>> entries = {{"tmpabc/main.plist", text_bytes(plist)},
                                                                             {"tmpabc/matrix.dat", matrix}};
  entries.push_back({"tmpabc/mask_0.dat", std::vector<unsigned char>(3 * 4 * 5, 1)});
  if (matrix_first) std::swap(entries[0], entries[1]);
  write_tar(p, entries, gzip);
}

}  // namespace

TEST(Inv3Files, ShapeIsZYXAndSamplesXFastest) {
  TempFolder dir;
  const fs::path p = dir / "small.inv3";
  write_project(p, kGoodPlist, int16_le(ramp_int16(4, 3, 2)));
  const ScalarVolume v = load_volume(p);
  EXPECT_EQ(v.dims, (std::array<int, 3>{4, 3, 2}));
  expect_column(v, 0, {0.5, 0, 0});
  expect_column(v, 1, {0, 0.625, 0});
  expect_column(v, 2, {0, 0, 1.25});
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) ASSERT_EQ(v.at(i, j, k), float(i + 10 * j + 100 * k));
}

TEST(Inv3Files, PlainTarAndMatrixBeforePlist) {
  TempFolder dir;
  const std::vector<std::int16_t> s = {-1024, 3071, -1, 0,  1,  256, -32768, 32767, 5,  6,  7,  8,
                                       9,     10,   11, 12, 13, 14,  15,     16,    17, 18, 19, 20};
  write_project(dir / "plain.inv3", kGoodPlist, int16_le(s), false, false);
  write_project(dir / "newer.inv3", kGoodPlist, int16_le(s), true, true);
  write_project(dir / "both.inv3", kGoodPlist, int16_le(s), true, false);
  for (const char* name : {"plain.inv3", "newer.inv3", "both.inv3"}) {
    const ScalarVolume v = load_volume(dir / name);
    ASSERT_EQ(v.values.size(), s.size()) << name;
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(v.values[i], float(s[i])) << name << " " << i;
  }
}

TEST(Inv3Files, ModalityFromThePlist) {
  TempFolder dir;
  write_project(dir / "mr.inv3", inv3_plist(inv3_matrix_dict(2, 3, 4), inv3_spacing(1, 1, 1), "MRI"),
                int16_le(ramp_int16(4, 3, 2)));
  const ScalarVolume v = load_volume(dir / "mr.inv3");
  EXPECT_EQ(v.modality, "MRI");
  EXPECT_EQ(v.units, "");
}

TEST(Inv3Malformed, MatrixOfTheWrongSize) {
  TempFolder dir;
  std::vector<unsigned char> short_matrix = int16_le(ramp_int16(4, 3, 2));
  short_matrix.pop_back();
  write_project(dir / "short.inv3", kGoodPlist, short_matrix);
  EXPECT_THAT(load_error(dir / "short.inv3"), AllOf(HasSubstr("holds 47 bytes"), HasSubstr("needs 48")));
  // A mask-like matrix, one sample larger on each axis (5×4×3) under the shape 2×3×4.
  write_project(dir / "plus1.inv3", kGoodPlist, int16_le(ramp_int16(5, 4, 3)));
  EXPECT_THAT(load_error(dir / "plus1.inv3"), HasSubstr("holds 120 bytes"));
}

TEST(Inv3Malformed, PlistWithMissingOrBadKeys) {
  TempFolder dir;
  const std::vector<unsigned char> m = int16_le(ramp_int16(4, 3, 2));
  const std::string matrix = inv3_matrix_dict(2, 3, 4), spacing = inv3_spacing(1, 1, 1);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {inv3_plist(matrix, ""), "no 'spacing'"},
      {inv3_plist("", spacing), "no 'matrix'"},
      {inv3_plist(matrix, inv3_spacing(1, 0, 1)), "spacing is not positive"},
      {inv3_plist(inv3_matrix_dict(2, 3, 4, "uint8"), spacing), "dtype is 'uint8'"},
      {inv3_plist(inv3_matrix_dict(2, 3, 4, "int16", "../matrix.dat"), spacing), "plain file name"},
      {inv3_plist(inv3_matrix_dict(2, 3, 1), spacing), "at least 2 per axis"},
      {inv3_plist(inv3_matrix_dict(2, -3, 4), spacing), "at least 2 per axis"},
      {inv3_plist("\t<key>matrix</key>\n\t<dict>\n\t\t<key>dtype</key>\n\t\t<string>int16</string>\n"
                  "\t\t<key>filename</key>\n\t\t<string>matrix.dat</string>\n\t\t<key>shape</key>\n"
                  "\t\t<array>\n\t\t\t<integer>2</integer>\n\t\t\t<integer>3</integer>\n\t\t</array>\n\t</dict>\n",
                  spacing),
       "no matrix 'shape' of 3 integers"},
      {"<plist version=\"1.0\"><dict><key>matrix</key>", "not readable XML"},
      {"<?xml version=\"1.0\"?><array/>", "not a property list"},
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const fs::path p = dir / ("case" + std::to_string(c) + ".inv3");
    write_project(p, cases[c].first, m);
    EXPECT_THAT(load_error(p), HasSubstr(cases[c].second)) << c;
  }
}

TEST(Inv3Malformed, ArchiveWithoutTheProjectFiles) {
  TempFolder dir;
  write_tar(dir / "nomatrix.inv3", {{"t/main.plist", text_bytes(kGoodPlist)}, {"t/other.dat", {1, 2}}});
  EXPECT_THAT(load_error(dir / "nomatrix.inv3"),
              HasSubstr("'t/matrix.dat' (named in main.plist) is not in the archive"));
  write_tar(dir / "noplist.inv3", {{"t/matrix.dat", int16_le(ramp_int16(4, 3, 2))}});
  EXPECT_THAT(load_error(dir / "noplist.inv3"), HasSubstr("no main.plist"));
  write_tar(dir / "empty.inv3", {});
  EXPECT_THAT(load_error(dir / "empty.inv3"), HasSubstr("no main.plist"));
}

TEST(Inv3Malformed, GarbageAndTruncatedArchives) {
  TempFolder dir;
  std::vector<unsigned char> garbage(5000);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<unsigned char>(i * 2654435761u >> 11);
  write_bytes(dir / "garbage.inv3", garbage);
  EXPECT_THAT(load_error(dir / "garbage.inv3"), HasSubstr("not an InVesalius project"));
  write_bytes(dir / "empty_file.inv3", nullptr, 0);
  EXPECT_THAT(load_error(dir / "empty_file.inv3"), HasSubstr("not an InVesalius project"));

  // A project whose gzip stream ends inside the matrix (poorly compressible samples, 512 KiB), and one cut short
  // in its first block.
  std::vector<std::int16_t> s(64 * 64 * 64);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<std::int16_t>(i * 2654435761u >> 16);
  const fs::path p = dir / "cut.inv3";
  write_project(p, inv3_plist(inv3_matrix_dict(64, 64, 64), inv3_spacing(1, 1, 1)), int16_le(s));
  EXPECT_EQ(load_volume(p).values.size(), s.size());
  const std::vector<unsigned char> whole = read_bytes(p);
  write_bytes(p, whole.data(), whole.size() / 2);
  EXPECT_THAT(load_error(p), AllOf(HasSubstr("matrix.dat"), HasSubstr("truncated")));
  write_bytes(p, whole.data(), 300);
  EXPECT_THAT(load_error(p), HasSubstr("truncated"));
}

TEST(Inv3Malformed, HugeShapeFailsBeforeAllocating) {
  TempFolder dir;
  const fs::path p = dir / "huge.inv3";
  write_project(p, inv3_plist(inv3_matrix_dict(30000, 30000, 30000), inv3_spacing(1, 1, 1)),
                int16_le(ramp_int16(4, 3, 2)));
  EXPECT_THAT(load_error(p), HasSubstr("over the memory budget"));
  VolumeLoadOptions huge;
  huge.memory_budget_bytes = std::uint64_t{1} << 62;
  const std::string why = load_error(p, huge);
  EXPECT_THAT(why, HasSubstr("holds 48 bytes"));
  EXPECT_THAT(why, ::testing::Not(HasSubstr("out of memory")));
}

// The fuzz targets' seeds (tests/fuzz/corpus/fuzz_volume_*): valid files load (mutations start from volumes that
// load), and the hostile ones (named hostile_*: bombs, absurd geometry, broken DICOM structure) are refused. A DICOM
// seed is one slice: load_volume refuses a series of one, so its slice is decoded on its own (load_dicom_slice).
TEST(VolumeFuzzSeeds, ValidSeedsLoadHostileSeedsAreRefused) {
  const fs::path corpus = fs::path(TRISPLINE_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
  int valid = 0, hostile = 0;
  VolumeLoadOptions fuzz_budget;
  fuzz_budget.memory_budget_bytes = std::uint64_t{256} << 20;  // what the fuzz targets load under
  for (const auto& [target, ext] : {std::pair{"fuzz_volume_nii", ".nii"}, std::pair{"fuzz_volume_nii_gz", ".nii.gz"},
                                    std::pair{"fuzz_volume_inv3", ".inv3"}, std::pair{"fuzz_volume_dicom", ".dcm"}}) {
    for (const auto& entry : fs::directory_iterator(corpus / target)) {
      TempFolder dir;
      const fs::path copy = dir / (std::string("input") + ext);  // the name the fuzz target gives it
      fs::copy_file(entry.path(), copy);
      const bool is_hostile = entry.path().filename().string().rfind("hostile_", 0) == 0;
      const auto load = [&] {
        if (std::string(ext) == ".dcm") return static_cast<std::size_t>(volume_io::load_dicom_slice(copy, fuzz_budget).size());
        return load_volume(copy, fuzz_budget).voxel_count();
      };
      if (is_hostile) {
        ++hostile;
        EXPECT_THROW(load(), VolumeLoadError) << entry.path();
      } else {
        ++valid;
        EXPECT_NO_THROW(load()) << entry.path();
      }
    }
  }
  EXPECT_EQ(valid, 16);
  EXPECT_EQ(hostile, 14);
}
