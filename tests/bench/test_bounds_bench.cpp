// `trispline bench bounds` (bench/bounds_bench.h) on a short sweep: the figures are there, the timing lattices are
// certified, and the sweep finds no unsound verdict (a certified lattice that sampling finds folded, or a fold
// reported where det J > 0); no triangle's measured error exceeds any of its bounds; the seed's cube refines to its
// certified tolerance with every split rule.
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
  o.soundness_triangles = 6000;
  const nlohmann::json r = core::run_bounds_benchmark(o);
  ASSERT_EQ(r.at("certificate").size(), 6u);
  for (const auto& c : r.at("certificate")) {
    EXPECT_EQ(c.at("verdict"), "fold_free") << c.dump();
    EXPECT_EQ(c.at("exact_verdict"), "fold_free") << c.dump();
    EXPECT_GE(c.at("exact_boxes").get<std::size_t>(), c.at("cells").get<std::size_t>()) << c.dump();
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
  const auto& s = r.at("soundness");
  EXPECT_EQ(s.at("triangles").get<std::size_t>(), 6000u);
  for (const char* m : {"right_triangle", "circumcircle", "enclosing_circle", "best", "normal"}) {
    EXPECT_EQ(s.at("methods").at(m).at("exceeded"), 0) << m;
    EXPECT_GE(s.at("methods").at(m).at("tightness").at("median").get<double>(), 1.0) << m;
  }
  ASSERT_EQ(r.at("refinement").size(), 6u);
  for (const auto& row : r.at("refinement"))
    for (const char* c : {"midpoint", "greville", "best"}) {
      EXPECT_EQ(row.at(c).at("stopped_by"), "converged") << row.dump();
      EXPECT_LE(row.at(c).at("max_bound").get<double>(), row.at("tolerance").get<double>()) << row.dump();
    }
  o.repeats = 0;
  EXPECT_THROW(core::run_bounds_benchmark(o), std::invalid_argument);
}
