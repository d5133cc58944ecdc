// `trispline bench bounds` (bench/bounds_bench.h) on a short sweep: the figures are there, the timing lattices are
// certified, and the sweep finds no unsound verdict (a certified lattice that sampling finds folded, or a fold
// reported where det J > 0).
#include <gtest/gtest.h>

#include <cmath>

#include "bench/bounds_bench.h"

using namespace trispline;

TEST(BoundsBench, ShortSweepIsSoundAndComplete) {
  core::BoundsBenchOptions o;
  o.repeats = 1;
  o.lattices = 96;
  o.mesh_path = "no-such-mesh.obj";  // the generated sphere, unrefined
  o.subdivision_level = 0;
  const nlohmann::json r = core::run_bounds_benchmark(o);
  ASSERT_EQ(r.at("certificate").size(), 6u);
  for (const auto& c : r.at("certificate")) {
    EXPECT_EQ(c.at("verdict"), "fold_free") << c.dump();
    EXPECT_GE(c.at("ms").get<double>(), 0.0);
  }
  const auto& w = r.at("sweep");
  EXPECT_EQ(w.at("lattices"), 96);
  EXPECT_EQ(w.at("certified_but_sampled_fold"), 0);
  EXPECT_EQ(w.at("fold_reported_at_positive_det"), 0);
  EXPECT_GT(w.at("fold_free").get<int>(), 10);
  EXPECT_GT(w.at("fold").get<int>(), 10);
  EXPECT_EQ(w.at("fold_free").get<int>() + w.at("fold").get<int>() + w.at("undecided").get<int>(), 96);
  const auto& t = r.at("triangles");
  EXPECT_EQ(t.at("mesh").at("fallback"), true);
  EXPECT_GT(t.at("triangles").get<std::size_t>(), 10000u);
  EXPECT_GT(t.at("max_bound").get<double>(), 0.0);
  EXPECT_TRUE(std::isfinite(t.at("max_bound").get<double>())) << "a cubic lattice bounds every triangle";
  o.repeats = 0;
  EXPECT_THROW(core::run_bounds_benchmark(o), std::invalid_argument);
}
