// Prepared volumes (core/volume/prepared_volume.h): the session cache returns the same spline and table for the same
// file, the disk cache serves a second session, and the default iso-level (226 HU for CT, else Otsu's threshold).
#include <gtest/gtest.h>

#include <unistd.h>

#include "core/volume/analytic_volumes.h"
#include "core/volume/prepared_volume.h"

namespace trispline::core {
namespace {

class PreparedVolumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("trispline_prepared_" + std::to_string(::getpid()));
    setenv("TRISPLINE_CACHE_DIR", dir_.c_str(), 1);
    clear_prepared_volumes();
  }
  void TearDown() override {
    clear_prepared_volumes();
    unsetenv("TRISPLINE_CACHE_DIR");
    std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
};

TEST_F(PreparedVolumeTest, SessionCacheThenDiskCache) {
  const PreparedVolume a = prepare_volume("analytic:torus", 4, false);
  EXPECT_FALSE(a.table_from_disk);
  const PreparedVolume b = prepare_volume("analytic:torus", 4, false);
  EXPECT_EQ(a.spline, b.spline);  // the session's copy
  EXPECT_EQ(a.table, b.table);
  const PreparedVolume c = prepare_volume("analytic:torus", 3, false);  // another order: another spline
  EXPECT_NE(c.spline, a.spline);
  clear_prepared_volumes();  // a new session: the table comes from the disk cache
  const PreparedVolume d = prepare_volume("analytic:torus", 4, false);
  EXPECT_TRUE(d.table_from_disk);
  EXPECT_EQ(d.table->cells_holding(0.0), a.table->cells_holding(0.0));
  EXPECT_THROW(prepare_volume("analytic:torus", 5, false), std::invalid_argument);
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
