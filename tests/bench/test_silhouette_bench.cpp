// `trispline bench silhouettes --orbit` (bench/silhouette_bench.h) on a real T1 MRI (insighttoolkit5-examples) with one
// view: the orbit's 36
// views run as one sequence, later views trace from the earlier ones' curves, and each view is checked against its
// complete extraction — the figures say how much of it the orbit found, and that is nearly all.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

// --views-out: the exact cameras of the timed views, in a file a peer reads (../shared/peers/vtk_silhouette.py takes
// its "views"): one per view, on the circle about the volume's centre, in the order they were timed.
TEST(SilhouetteBench, ViewsOutWritesTheCamerasOfTheTimedViews) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "silhouette_views_out";
  std::filesystem::create_directories(dir);
  core::SilhouetteBenchOptions o;
  o.volume_path = "analytic:sphere";
  o.iso = 0.0;
  o.views = 3;
  o.views_out = (dir / "views.json").string();
  const nlohmann::json r = core::run_silhouette_benchmark(o);
  EXPECT_EQ(r.at("views_out"), o.views_out);
  std::ifstream f(o.views_out);
  const nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_EQ(j.at("views").size(), 3u);
  EXPECT_FALSE(j.contains("orbit_views"));
  double distance = -1.0;
  for (std::size_t v = 0; v < 3; ++v) {
    const nlohmann::json& c = j["views"][v];
    EXPECT_EQ(c.at("name"), "view_" + std::to_string(v));
    EXPECT_NEAR(c.at("azimuth_deg").get<double>(), 120.0 * v, 1e-9);
    EXPECT_EQ(c.at("target"), j["views"][0].at("target")) << "every view looks at the volume's centre";
    EXPECT_EQ(c.at("viewport"), nlohmann::json::array({1280, 720}));
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double d = c["eye"][a].get<double>() - c["target"][a].get<double>();
      d2 += d * d;
    }
    if (distance < 0.0) distance = std::sqrt(d2);
    EXPECT_NEAR(std::sqrt(d2), distance, 1e-9 * distance) << "the eyes lie on one circle";
    EXPECT_GT(distance, 0.0);
  }
  // The file is written before the first view: a folder that does not exist is refused before any work.
  o.views_out = (dir / "missing" / "views.json").string();
  EXPECT_THROW(core::run_silhouette_benchmark(o), std::runtime_error);
}
