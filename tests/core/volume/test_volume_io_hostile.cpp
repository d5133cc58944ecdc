// load_volume on hostile NIfTI and .inv3 files the test writes itself: decompression bombs refused on their header's
// dimensions before a byte is inflated (the memory budget with the caller's extra bytes per voxel; peak RSS), absurd
// or non-finite geometry refused naming the field (sform, qform, pixdim, units, .inv3 spacing), and a damaged gzip
// stream reported with zlib's reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/volume/volume_io.h"
#include "core/volume/volume_io_formats.h"
#include "tests/core/volume/volume_test_files.h"

namespace fs = std::filesystem;
using namespace trispline::core;
using namespace trispline::test;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// A NIfTI-1 header for nx×ny×nz uint8 samples at vox_offset 352, as bytes (header + 4-byte extender).
std::vector<unsigned char> uint8_nifti_header(int nx, int ny, int nz) {
  nifti_1_header h{};
  h.sizeof_hdr = 348;
  h.dim[0] = 3, h.dim[1] = static_cast<short>(nx), h.dim[2] = static_cast<short>(ny), h.dim[3] = static_cast<short>(nz);
  h.dim[4] = h.dim[5] = h.dim[6] = h.dim[7] = 1;
  h.datatype = DT_UINT8;
  h.bitpix = 8;
  for (float& p : h.pixdim) p = 1.0f;
  h.vox_offset = 352.0f;
  h.xyzt_units = NIFTI_UNITS_MM;
  std::memcpy(h.magic, "n+1", 4);
  std::vector<unsigned char> bytes(352, 0);
  std::memcpy(bytes.data(), &h, sizeof h);
  return bytes;
}

// A valid 8×8×8 int16 .nii to break.
fs::path small_nifti(const TempFolder& dir) {
  const fs::path p = dir / "small.nii";
  write_nifti(p, {8, 8, 8}, DT_INT16, std::vector<unsigned char>(8 * 8 * 8 * 2, 1));
  return p;
}

}  // namespace

// ------------------------------------------------------------------------------------------------ budgets

// 580³ zeros gzip'd: ~190 KB on disk, 195 MB of samples, 780 MB as floats. With what the caller spends per voxel
// after the load it cannot fit, and that is known from the header alone.
TEST(VolumeBombs, GzipNiftiRefusedOnItsHeaderDimensions) {
  TempFolder dir;
  const fs::path p = dir / "zeros.nii.gz";
  write_deflated(p, {}, uint8_nifti_header(580, 580, 580), std::uint64_t{580} * 580 * 580, true);
  ASSERT_LT(fs::file_size(p), std::uintmax_t{1} << 20);
  const std::uint64_t before = peak_rss_bytes();
  VolumeLoadOptions options;
  options.extra_bytes_per_voxel = 24;
  const std::string why = volume_load_error(p, options);
  EXPECT_THAT(why, AllOf(HasSubstr("580×580×580"), HasSubstr("over the memory budget of 4.0 GiB"),
                         HasSubstr("24 bytes a voxel"), HasSubstr("5464184576 bytes")));
  VolumeLoadOptions small;
  small.memory_budget_bytes = std::uint64_t{512} << 20;
  EXPECT_THAT(volume_load_error(p, small), AllOf(HasSubstr("580×580×580"), HasSubstr("512.0 MiB")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{100} << 20) << "samples were read before the budget refused";
}

TEST(VolumeBombs, Inv3RefusedOnItsPlistShape) {
  TempFolder dir;
  const fs::path p = dir / "zeros.inv3";
  // 600³ int16 zeros (432 MB) in a gzip'd tar, its matrix entry written as a stream.
  const std::uint64_t matrix = std::uint64_t{600} * 600 * 600 * 2;
  archive* a = archive_write_new();
  archive_write_add_filter_gzip(a);
  archive_write_set_format_pax_restricted(a);
  ASSERT_EQ(archive_write_open_filename(a, p.c_str()), ARCHIVE_OK);
  const std::string plist = inv3_plist(inv3_matrix_dict(600, 600, 600), inv3_spacing(0.5, 0.5, 0.5));
  for (const auto& [name, size] : {std::pair<std::string, std::uint64_t>{"p/main.plist", plist.size()},
                                   std::pair<std::string, std::uint64_t>{"p/matrix.dat", matrix}}) {
    archive_entry* e = archive_entry_new();
    archive_entry_set_pathname(e, name.c_str());
    archive_entry_set_size(e, static_cast<la_int64_t>(size));
    archive_entry_set_filetype(e, AE_IFREG);
    archive_entry_set_perm(e, 0644);
    archive_write_header(a, e);
    if (name == "p/main.plist") {
      archive_write_data(a, plist.data(), plist.size());
    } else {
      const std::vector<char> zeros(1 << 20, 0);
      for (std::uint64_t left = matrix; left > 0; left -= std::min<std::uint64_t>(left, zeros.size()))
        archive_write_data(a, zeros.data(), static_cast<std::size_t>(std::min<std::uint64_t>(left, zeros.size())));
    }
    archive_entry_free(e);
  }
  archive_write_close(a);
  archive_write_free(a);
  ASSERT_LT(fs::file_size(p), std::uintmax_t{2} << 20);
  const std::uint64_t before = peak_rss_bytes();
  VolumeLoadOptions options;
  options.memory_budget_bytes = std::uint64_t{1} << 30;
  options.extra_bytes_per_voxel = 4;
  EXPECT_THAT(
      volume_load_error(p, options),
      AllOf(HasSubstr("600×600×600"), HasSubstr("over the memory budget of 1.0 GiB"), HasSubstr("4 bytes a voxel")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{100} << 20);
}

// ---------------------------------------------------------------------------------------------- geometry

TEST(VolumeGeometry, NiftiSformBeyondTheWorldIsRefusedNamingIt) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  const auto patch_sform = [&](float scale, float offset, int units) {
    write_bytes(p, good);
    patch_nifti_header(p, [&](nifti_1_header& h) {
      h.sform_code = 1;
      h.srow_x[0] = h.srow_y[1] = h.srow_z[2] = scale;
      h.srow_x[3] = offset;
      h.xyzt_units = static_cast<char>(units);
    });
  };
  const auto sform = [&](float scale, float offset, int units) {
    patch_sform(scale, offset, units);
    return volume_load_error(p);
  };
  EXPECT_THAT(sform(3e38f, 0, NIFTI_UNITS_MM), AllOf(HasSubstr("sform"), HasSubstr("3e+38 mm")));
  EXPECT_THAT(sform(1e37f, 0, NIFTI_UNITS_METER), AllOf(HasSubstr("sform"), HasSubstr("metres")));
  EXPECT_THAT(sform(1e-12f, 0, NIFTI_UNITS_MM), AllOf(HasSubstr("sform"), HasSubstr("a voxel may span")));
  EXPECT_THAT(sform(1, 2e9f, NIFTI_UNITS_MM), AllOf(HasSubstr("sform"), HasSubstr("1000 km")));
  EXPECT_THAT(sform(1e5f, 0, NIFTI_UNITS_METER), HasSubstr("1e+08 mm"));  // 100 km voxels
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) {
    h.sform_code = 1;
    h.srow_x[0] = h.srow_y[1] = h.srow_z[2] = 1.0f;
    h.srow_z[3] = std::numeric_limits<float>::quiet_NaN();
  });
  EXPECT_THAT(volume_load_error(p), AllOf(HasSubstr("sform"), HasSubstr("not finite")));
  // 1 m voxels are 1000 mm: in range, and loaded as such.
  patch_sform(1, 0, NIFTI_UNITS_METER);
  EXPECT_EQ(load_volume(p).index_to_world[1][1], 1000.0);
}

TEST(VolumeGeometry, NiftiPixdimAndQuaternionAreRefusedNotRepaired) {
  TempFolder dir;
  const fs::path p = small_nifti(dir);
  const std::vector<unsigned char> good = read_bytes(p);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const float bad : {0.0f, -1.0f, nan, std::numeric_limits<float>::infinity()}) {
    for (const int qform : {0, 1}) {  // diag(pixdim), or the qform's scales
      write_bytes(p, good);
      patch_nifti_header(p, [&](nifti_1_header& h) {
        h.qform_code = static_cast<short>(qform);
        h.pixdim[2] = bad;
      });
      EXPECT_THAT(volume_load_error(p), AllOf(HasSubstr("pixdim[2]"), HasSubstr(qform ? "qform" : "no sform")))
          << bad << " qform " << qform;
    }
  }
  // With an sform, pixdim is not used: a zero there is no reason to refuse.
  write_bytes(p, good);
  patch_nifti_header(p, [](nifti_1_header& h) {
    h.sform_code = 1;
    h.srow_x[0] = h.srow_y[1] = h.srow_z[2] = 1.0f;
    h.pixdim[1] = 0.0f;
  });
  EXPECT_NO_THROW(load_volume(p));
  for (const auto& [qb, qc, qd] : {std::tuple{nan, 0.0f, 0.0f}, std::tuple{0.9f, 0.9f, 0.0f}}) {
    const float b = qb, c = qc, d = qd;  // clang 14 cannot capture structured bindings
    write_bytes(p, good);
    patch_nifti_header(p, [&](nifti_1_header& h) {
      h.qform_code = 1;
      h.quatern_b = b, h.quatern_c = c, h.quatern_d = d;
    });
    EXPECT_THAT(volume_load_error(p), HasSubstr("quaternion")) << b << " " << c;
  }
  write_bytes(p, good);
  patch_nifti_header(p, [&](nifti_1_header& h) {
    h.qform_code = 1;
    h.qoffset_y = nan;
  });
  EXPECT_THAT(volume_load_error(p), HasSubstr("qoffset"));
}

TEST(VolumeGeometry, Inv3SpacingOutOfRangeIsRefused) {
  TempFolder dir;
  const auto spacing = [](const std::string& y) {
    return "\t<key>spacing</key>\n\t<array>\n\t\t<real>1</real>\n\t\t<real>" + y +
           "</real>\n\t\t<real>1</real>\n\t</array>\n";
  };
  for (const auto& [y, why] : {std::pair{"1e100", "1e+100 mm"}, std::pair{"1e-9", "a voxel may span"}}) {
    const fs::path p = dir / "spacing.inv3";
    write_tar(p, {{"p/main.plist", text_bytes(inv3_plist(inv3_matrix_dict(2, 3, 4), spacing(y)))},
                  {"p/matrix.dat", std::vector<unsigned char>(48, 0)}});
    EXPECT_THAT(volume_load_error(p), AllOf(HasSubstr("main.plist's spacing"), HasSubstr(why))) << y;
  }
  // 1 km voxels are in range, but 1002 of them along y reach past 1000 km.
  const fs::path p = dir / "far.inv3";
  write_tar(p, {{"p/main.plist", text_bytes(inv3_plist(inv3_matrix_dict(2, 1002, 2), spacing("1e6")))},
                {"p/matrix.dat", std::vector<unsigned char>(2 * 1002 * 2 * 2, 0)}});
  EXPECT_THAT(volume_load_error(p), AllOf(HasSubstr("main.plist's spacing"), HasSubstr("1000 km")));
}

TEST(VolumeMessages, DamagedGzipNamesZlibsReason) {
  TempFolder dir;
  const fs::path p = dir / "small.nii.gz";
  write_nifti(p, {8, 8, 8}, DT_INT16, std::vector<unsigned char>(8 * 8 * 8 * 2, 7));
  const std::vector<unsigned char> good = read_bytes(p);
  for (const std::size_t from_end : {8u, 4u}) {  // the CRC, the length
    std::vector<unsigned char> bytes = good;
    bytes[bytes.size() - from_end] ^= 0xFF;
    write_bytes(p, bytes);
    const std::string why = volume_load_error(p);
    EXPECT_THAT(why, AllOf(HasSubstr("check at its end (CRC-32 and length) does not match"), HasSubstr("zlib: "),
                           Not(HasSubstr("in the header")), Not(HasSubstr("18446744073709551615"))))
        << from_end;
  }
  std::vector<unsigned char> bytes = good;
  bytes[bytes.size() / 2] ^= 0x55;  // inside the deflate data
  write_bytes(p, bytes);
  EXPECT_THAT(volume_load_error(p), AllOf(Not(HasSubstr("18446744073709551615")), HasSubstr("small.nii.gz")));
}

// ------------------------------------------------------------------------------------------------ fuzz seeds

// The fuzz targets' seeds (tests/fuzz/corpus/fuzz_volume_*): valid files load (mutations start from volumes that
// load), and the hostile ones (named hostile_*: bombs, absurd geometry, broken DICOM structure) are refused. A DICOM
// seed is one slice: load_volume refuses a series of one, so its slice is decoded on its own (load_dicom_slice).
TEST(VolumeFuzzSeeds, ValidSeedsLoadHostileSeedsAreRefused) {
  const fs::path corpus = fs::path(TRISPLINE_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
  int valid = 0, hostile = 0;
  VolumeLoadOptions fuzz_budget;
  fuzz_budget.memory_budget_bytes = std::uint64_t{256} << 20;  // what the fuzz targets load under
  for (const auto& [target, extension] :
       {std::pair{"fuzz_volume_nii", ".nii"}, std::pair{"fuzz_volume_nii_gz", ".nii.gz"},
        std::pair{"fuzz_volume_inv3", ".inv3"}, std::pair{"fuzz_volume_dicom", ".dcm"}}) {
    const std::string ext = extension;  // clang 14 cannot capture structured bindings
    for (const auto& entry : fs::directory_iterator(corpus / target)) {
      TempFolder dir;
      const fs::path copy = dir / (std::string("input") + ext);  // the name the fuzz target gives it
      fs::copy_file(entry.path(), copy);
      const bool is_hostile = entry.path().filename().string().rfind("hostile_", 0) == 0;
      const auto load = [&] {
        if (ext == ".dcm") return static_cast<std::size_t>(volume_io::load_dicom_slice(copy, fuzz_budget).size());
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
