// The FFD benchmark (bench/ffd_bench.h): one small run on the generated fallback sphere (smoke), bad options.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "bench/ffd_bench.h"

using namespace trispline::core;

TEST(Benchmark, SmokeRunWithFallbackMesh) {
  FfdBenchOptions o;
  o.mesh_path = "/nonexistent/bunny.obj";
  o.subdivision_level = 0;
  o.runs = 1;
  o.lattices = {4};
  o.orders = {3};
  const nlohmann::json r = run_ffd_benchmark(o);
  EXPECT_TRUE(r.at("mesh").at("fallback").get<bool>());
  EXPECT_GT(r.at("mesh").at("vertices").get<int>(), 30000);
  bool saw_fast = false;
  for (const auto& c : r.at("cases")) {
    EXPECT_LE(c.at("max_err_rel").get<double>(), 1e-5) << c.dump();
    saw_fast = saw_fast || c.at("backend") == "cpu_fast";
  }
  EXPECT_TRUE(saw_fast);
  std::ostringstream os;
  print_ffd_benchmark(r, os);
  EXPECT_NE(os.str().find("not found"), std::string::npos);
  o.orders = {5};
  EXPECT_THROW(run_ffd_benchmark(o), std::invalid_argument);
}
