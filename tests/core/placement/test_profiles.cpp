// Variable width and height of the placement volume (seed §2.4.1, Eq. 2.5): d(u) scales the offsets across the
// stroke, h(u) or h(u,v) the height of each column over the contact surface.
#include <gtest/gtest.h>

#include "placement_test_util.h"
#include "tests/error_field.h"

namespace trispline::core::test {
namespace {

TriMesh flat_ground() {
  return height_field(5.0, 20, [](double, double) { return 0.0; });
}
TriMesh small_box() { return tessellated_box({2.0, 0.5, 0.6}, {5.0, 5.0, 5.0}, 4); }

// Linear interpolation of samples spread uniformly over [0,1] (what the profiles mean).
double lerp_profile(const std::vector<double>& s, double t) {
  const double x = t * (s.size() - 1);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), s.size() - 2);
  return s[k] + (x - k) * (s[k + 1] - s[k]);
}

// Every column of the lattice F, |P(i, j, top) − P(i, j, 0)|, is want(i, j) within 1e-12.
template <class Lattice, class Want>
void expect_column_heights(const Lattice& F, Want want) {
  const glm::ivec3 n = F.control_counts();
  for (int j = 0; j < n.y; ++j)
    for (int i = 0; i < n.x; ++i) {
      const double column = glm::length(F.control_point(i, j, n.z - 1) - F.control_point(i, j, 0));
      EXPECT_NEAR(column, want(i, j), 1e-12) << i << "," << j;
    }
}

TEST(PlacementProfiles, HeightProfileOfUScalesEveryColumn) {
  const RayCaster rc = caster_for(flat_ground());
  SketchPlacementParams p = default_params(straight_stroke());
  p.height_profile = {{1.0, 3.0, 2.0}};
  const SketchPlacementResult r = place_along_stroke(rc, p, small_box().positions);
  const auto gu = r.binding.lattice.knots(0).greville();
  expect_column_heights(r.binding.lattice,
                        [&](int i, int) { return p.height * lerp_profile(p.height_profile[0], gu[i]); });
}

TEST(PlacementProfiles, HeightProfileOfUVIsBilinearOverTheColumns) {
  const RayCaster rc = caster_for(flat_ground());
  SketchPlacementParams p = default_params(straight_stroke());
  p.height_profile = {{1.0, 1.0}, {3.0, 3.0}};  // 1 on the v = 0 side, 3 on the v = 1 side
  const SketchPlacementResult r = place_along_stroke(rc, p, small_box().positions);
  const auto gv = r.binding.lattice.knots(1).greville();
  expect_column_heights(r.binding.lattice, [&](int, int j) { return p.height * (1.0 + 2.0 * gv[j]); });
}

TEST(PlacementProfiles, WidthProfileScalesTheContactGridAcrossTheStroke) {
  const RayCaster rc = caster_for(flat_ground());
  SketchPlacementParams p = default_params(straight_stroke());
  const SketchPlacementResult plain = place_along_stroke(rc, p, small_box().positions);
  p.width_profile = {1.0, 0.5, 2.0};
  const SketchPlacementResult shaped = place_along_stroke(rc, p, small_box().positions);
  const int nu = p.samples_u, nv = p.samples_v;
  const auto across = [&](const SketchPlacementResult& r, int i) {
    return glm::length(r.record.contact_points[i + nu * (nv - 1)] - r.record.contact_points[i]);
  };
  for (int i = 0; i < nu; ++i) {
    const double f = lerp_profile(p.width_profile, static_cast<double>(i) / (nu - 1));
    // Top-down view of a flat plane: image-plane offsets map linearly onto the ground.
    EXPECT_NEAR(across(shaped, i), f * across(plain, i), 1e-9 * across(plain, i)) << "sample " << i;
  }
  EXPECT_GT(shaped.stats.min_det_jacobian, 0.0);
}

TEST(PlacementProfiles, BadProfilesNameTheirField) {
  const RayCaster rc = caster_for(flat_ground());
  const auto field_of = [&](const SketchPlacementParams& p) {
    return trispline::test::field_of<PlacementError>([&] { place_along_stroke(rc, p, small_box().positions); });
  };
  SketchPlacementParams p = default_params(straight_stroke());
  p.width_profile = {1.0, 0.0};
  EXPECT_EQ(field_of(p), "width_profile");
  p.width_profile = {1.0};
  EXPECT_EQ(field_of(p), "width_profile");
  p.width_profile = {1.0, std::nan("")};
  EXPECT_EQ(field_of(p), "width_profile");
  p.width_profile.clear();
  p.height_profile = {{1.0, 2.0}, {1.0, 2.0, 3.0}};
  EXPECT_EQ(field_of(p), "height_profile");
  p.height_profile = {{1.0, -2.0}};
  EXPECT_EQ(field_of(p), "height_profile");
}

}  // namespace
}  // namespace trispline::core::test
