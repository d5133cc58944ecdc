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
