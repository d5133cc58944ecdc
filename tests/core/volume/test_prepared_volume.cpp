// Prepared volumes (core/volume/prepared_volume.h): the session cache returns the same spline and table for the same
// file, a second session prepares the same table again, the default iso-level (226 HU for CT, else Otsu's threshold),
// and the preparation budget (preparation_budget.h): dimensions whose spline and table would not fit are refused from
// the header, before the file is inflated.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>

#include "core/volume/analytic_volumes.h"
#include "core/volume/prepared_volume.h"

namespace trispline::core {
namespace {

class PreparedVolumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("trispline_prepared_" + std::to_string(::getpid()));
    clear_prepared_volumes();
  }
  void TearDown() override {
    clear_prepared_volumes();
    std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
};

TEST_F(PreparedVolumeTest, SessionCacheThenTheSameTableAgain) {
  const PreparedVolume a = prepare_volume("analytic:torus", 4, false);
  const PreparedVolume b = prepare_volume("analytic:torus", 4, false);
  EXPECT_EQ(a.spline, b.spline);  // the session's copy
  EXPECT_EQ(a.table, b.table);
  const PreparedVolume c = prepare_volume("analytic:torus", 3, false);  // another order: another spline
  EXPECT_NE(c.spline, a.spline);
  clear_prepared_volumes();  // a new session prepares again, and gets the same table (deterministic preparation)
  const PreparedVolume d = prepare_volume("analytic:torus", 4, false);
  EXPECT_NE(d.table, a.table);
  ASSERT_EQ(d.table->cell_count(), a.table->cell_count());
  EXPECT_EQ(std::memcmp(d.table->singletons().data(), a.table->singletons().data(),
                        a.table->cell_count() * sizeof(Singleton)),
            0);
  EXPECT_EQ(d.table->cells_holding(0.0), a.table->cells_holding(0.0));
  EXPECT_THROW(prepare_volume("analytic:torus", 5, false), std::invalid_argument);
}

TEST(PreparationBudget, FortyBytesPerSampleFromTheDimensions) {
  EXPECT_EQ(4 + kPreparationBytesPerVoxel, 40u);
  // Cranium (256×256×108, order 4): 7.08 M samples × 40 bytes plus the macro-cells and the fixed tables.
  const std::uint64_t cranium = preparation_bytes({256, 256, 108}, 4);
  EXPECT_GE(cranium, 256ull * 256 * 108 * 40);
  EXPECT_LE(cranium, 256ull * 256 * 108 * 40 + (2ull << 20));
  EXPECT_NO_THROW(check_preparation_budget("cranium", {256, 256, 108}, 4));
  // Odd orders have one more cell per axis; the figure still bounds them.
  EXPECT_GE(preparation_bytes({256, 256, 108}, 3), preparation_bytes({256, 256, 108}, 4));
  // Absurd header dimensions saturate instead of wrapping around to a small figure.
  const std::int64_t big = std::numeric_limits<std::int32_t>::max();
  EXPECT_EQ(preparation_bytes({big, big, big}, 4), std::numeric_limits<std::uint64_t>::max());
  EXPECT_GT(preparation_bytes({big, big, 2}, 2), kPreparedVolumeBudget);
}

TEST(PreparationBudget, RefusalNamesTheDimensionsTheBytesAndTheBudget) {
  try {
    check_preparation_budget("x.nii.gz", {580, 580, 580}, 4);
    FAIL() << "580³ samples fit the budget";
  } catch (const PreparationBudgetError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("x.nii.gz"), std::string::npos) << m;
    EXPECT_NE(m.find("580×580×580"), std::string::npos) << m;
    EXPECT_NE(m.find("7448 MiB"), std::string::npos) << m;  // 580³ × 40 bytes + tables, rounded up
    EXPECT_NE(m.find("order 4"), std::string::npos) << m;
    EXPECT_NE(m.find("memory budget of 6144 MiB"), std::string::npos) << m;
  }
  // Just under and just over: 160 M samples fit, 162 M do not.
  EXPECT_NO_THROW(check_preparation_budget("a", {1000, 1000, 160}, 4));
  EXPECT_THROW(check_preparation_budget("a", {1000, 1000, 162}, 4), PreparationBudgetError);
  EXPECT_THROW(check_preparation_budget("a", {64, 64, 64}, 4, 1 << 20), PreparationBudgetError);  // a smaller budget
}

// A .nii.gz of 580³ uint8 samples whose gzip stream stops after the header and a few zeros: the dimensions alone
// decide; the loader refuses before it inflates the samples.
TEST_F(PreparedVolumeTest, OverBudgetFileIsRefusedFromItsHeader) {
  std::filesystem::create_directories(dir_);
  const auto path = dir_ / "zeros_580.nii.gz";
  unsigned char header[352] = {};
  const std::int32_t sizeof_hdr = 348;
  const std::int16_t dim[8] = {3, 580, 580, 580, 1, 1, 1, 1}, datatype = 2, bitpix = 8;
  const float pixdim[8] = {1, 1, 1, 1, 1, 1, 1, 1}, vox_offset = 352;
  std::memcpy(header, &sizeof_hdr, 4);
  std::memcpy(header + 40, dim, sizeof(dim));
  std::memcpy(header + 70, &datatype, 2);
  std::memcpy(header + 72, &bitpix, 2);
  std::memcpy(header + 76, pixdim, sizeof(pixdim));
  std::memcpy(header + 108, &vox_offset, 4);
  std::memcpy(header + 344, "n+1", 4);
  gzFile f = gzopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, header, sizeof(header));
  const std::vector<unsigned char> zeros(1 << 16, 0);
  gzwrite(f, zeros.data(), static_cast<unsigned>(zeros.size()));
  gzclose(f);
  try {
    prepare_volume(path, 4, false);
    FAIL() << "a 580³ volume was prepared";
  } catch (const VolumeLoadError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("budget"), std::string::npos) << m;
    EXPECT_NE(m.find(path.filename().string()), std::string::npos) << m;
  }
}

TEST_F(PreparedVolumeTest, BadOrderIsRefusedBeforeReading) {
  // A missing file with a bad order: the order is named, not the file.
  try {
    prepare_volume(dir_ / "missing.nii", 5, false);
    FAIL();
  } catch (const VolumeLoadError&) {
    FAIL() << "the file was read before the order was checked";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("order"), std::string::npos) << e.what();
  }
}

TEST(DefaultIsoLevel, BoneForCtElseOtsu) {
  ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 24);
  // Two classes: background 10, object 90 (and a little spread): Otsu's level lies between them.
  for (float& x : v.values) x = x > 0.0f ? 90.0f + 0.01f * x : 10.0f + 0.01f * x;
  const double level = default_iso_level(v);
  EXPECT_GT(level, 15.0);
  EXPECT_LT(level, 85.0);
  v.units = "HU";
  EXPECT_EQ(default_iso_level(v), 226.0);
}

}  // namespace
}  // namespace trispline::core
