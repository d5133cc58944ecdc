// `trispline bench silhouettes --orbit` (bench/silhouette_bench.h) on a real T1 MRI (insighttoolkit5-examples) with one
// view: the orbit's 36
// views run as one sequence, later views trace from the earlier ones' curves, and each view is checked against its
// complete extraction — the figures say how much of it the orbit found, and that is nearly all.
#include <gtest/gtest.h>

#include <filesystem>

#include "bench/silhouette_bench.h"

using namespace trispline;

TEST(SilhouetteBench, OrbitRunsAsASequenceAndCoversTheCompleteExtraction) {
  core::SilhouetteBenchOptions o;
  o.volume_path = (std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/KmeansTest_T1UCharRaw.nii.gz").string();
  o.iso = 46.8;
  o.views = 1;
  o.orbit = true;
  const nlohmann::json r = core::run_silhouette_benchmark(o);
  ASSERT_EQ(r.at("orbit_views").size(), 36u);
  EXPECT_EQ(r.at("orbit_views")[0].at("traced_from_previous"), 0u);
  std::size_t from_previous = 0;
  for (const auto& v : r.at("orbit_views")) {
    from_previous += v.at("traced_from_previous").get<std::size_t>();
    EXPECT_GT(v.at("visible_points").get<std::size_t>(), 0u) << v.dump();
    EXPECT_LE(v.at("visible_points").get<std::size_t>(), v.at("points").get<std::size_t>());
  }
  EXPECT_GT(from_previous, 100u);
  EXPECT_GE(r.at("orbit_min_coverage").get<double>(), 0.98);
  EXPECT_LE(r.at("orbit_median_coverage").get<double>(), 1.0);
  EXPECT_GT(r.at("orbit_median_view_ms").get<double>(), 0.0);
  EXPECT_GE(r.at("peak_rss_mb").get<double>(), r.at("prep_rss_mb").get<double>());
}
