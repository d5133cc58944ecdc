// The pressing tools' falloff profiles (core/ffd/falloff.h): 1 at the centre, 0 at and beyond the radius, never
// increasing in between; names round-trip.
#include <gtest/gtest.h>

#include <string_view>

#include "core/ffd/falloff.h"

using namespace trispline;

namespace {

TEST(Falloff, ProfilesAreOneAtTheCentreZeroOutsideAndNonIncreasing) {
  for (std::string_view name : core::kFalloffNames) {
    const auto f = core::parse_falloff(name);
    ASSERT_TRUE(f) << name;
    EXPECT_EQ(core::to_string(*f), name);
    EXPECT_DOUBLE_EQ(core::falloff_weight(*f, 0.0), 1.0) << name;
    EXPECT_EQ(core::falloff_weight(*f, 1.0), 0.0) << name;
    EXPECT_EQ(core::falloff_weight(*f, 1.5), 0.0) << name;
    double prev = 1.0;
    for (int i = 1; i < 100; ++i) {
      const double w = core::falloff_weight(*f, i / 100.0);
      EXPECT_LE(w, prev + 1e-15) << name << " at " << i / 100.0;
      EXPECT_GT(w, 0.0) << name;
      prev = w;
    }
  }
  EXPECT_NEAR(core::falloff_weight(core::Falloff::hat, 0.25), 0.75, 1e-15);
  EXPECT_NEAR(core::falloff_weight(core::Falloff::sharp, 0.5), 0.25, 1e-15);
  EXPECT_NEAR(core::falloff_weight(core::Falloff::sphere, 0.6), 0.8, 1e-15);
  EXPECT_FALSE(core::parse_falloff("inverse_square"));
}

}  // namespace
