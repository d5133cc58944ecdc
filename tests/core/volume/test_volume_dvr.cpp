// Direct volume rendering, CPU reference (core/volume/volume_dvr.h): the transfer function's interpolation, its
// refusals, the emission–absorption compositing against closed forms on a constant volume, and that empty-space
// skipping by bricks changes no bit of an image of the sphere test volume.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/volume/volume_dvr.h"
#include "core/volume/volume_spline.h"
#include "tests/core/volume/iso_test_volumes.h"

using namespace trispline::core;

namespace {

TransferFunction ramp() {
  return {{{0.0, {0.0, 0.0, 0.0, 0.0}}, {10.0, {1.0, 0.5, 0.0, 0.4}}, {20.0, {0.0, 1.0, 1.0, 1.0}}}};
}

double srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

// A volume of constant value `v` on an n³ grid of unit spacing at the origin.
VolumeSpline constant_volume(float v, int n = 9) {
  ScalarVolume s;
  s.dims = {n, n, n};
  s.values.assign(std::size_t(n) * n * n, v);
  s.source = "constant";
  return VolumeSpline(s, 4, false);
}

}  // namespace

TEST(TransferFunction, InterpolatesLinearlyAndClampsBeyondItsEnds) {
  const TransferFunction tf = ramp();
  EXPECT_EQ(tf.at(-5.0), glm::dvec4(0.0));
  EXPECT_EQ(tf.at(25.0), glm::dvec4(0.0, 1.0, 1.0, 1.0));
  const glm::dvec4 mid = tf.at(5.0);
  EXPECT_DOUBLE_EQ(mid.x, 0.5);
  EXPECT_DOUBLE_EQ(mid.w, 0.2);
  EXPECT_DOUBLE_EQ(tf.at(15.0).w, 0.7);
  EXPECT_EQ(tf.at(std::nan("")), tf.points.front().rgba);
  EXPECT_DOUBLE_EQ(tf.max_opacity(-10.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(tf.max_opacity(-10.0, 12.0), tf.at(12.0).w);
  EXPECT_DOUBLE_EQ(tf.max_opacity(9.0, 11.0), tf.at(11.0).w);
  EXPECT_DOUBLE_EQ(tf.max_opacity(5.0, 30.0), 1.0);
}

TEST(TransferFunction, RefusesWhatCannotBeDrawn) {
  EXPECT_EQ(transfer_function_error(ramp()), "");
  EXPECT_EQ(transfer_function_error(ct_transfer_function()), "");
  TransferFunction one{{{0.0, glm::dvec4(0.5)}}};
  EXPECT_NE(transfer_function_error(one).find("2 to 16"), std::string::npos);
  TransferFunction down = ramp();
  down.points[2].value = 5.0;
  EXPECT_NE(transfer_function_error(down).find("point 2"), std::string::npos);
  TransferFunction bright = ramp();
  bright.points[1].rgba.y = 1.5;
  EXPECT_NE(transfer_function_error(bright).find("[0, 1]"), std::string::npos);
  TransferFunction nan = ramp();
  nan.points[0].value = std::nan("");
  EXPECT_NE(transfer_function_error(nan).find("finite"), std::string::npos);
  TransferFunction many;
  for (int i = 0; i < 17; ++i) many.points.push_back({double(i), glm::dvec4(0.5)});
  EXPECT_NE(transfer_function_error(many), "");
  const VolumeSpline s = constant_volume(5.0f);
  EXPECT_THROW(dvr_ray(s, one, glm::dvec3(4, 4, -10), glm::dvec3(0, 0, 1)), std::invalid_argument);
  EXPECT_THROW(dvr_ray(s, ramp(), glm::dvec3(4, 4, -10), glm::dvec3(0, 0, 1), 0.0), std::invalid_argument);
  EXPECT_THROW(dvr_ray(s, ramp(), glm::dvec3(4, 4, -10), glm::dvec3(0.0)), std::invalid_argument);
  EXPECT_THROW(dvr_ray(s, ramp(), glm::dvec3(std::nan(""), 4, -10), glm::dvec3(0, 0, 1)), std::invalid_argument);
}

TEST(DvrRay, ConstantVolumeComposesAsTheClosedForm) {
  // D = 5 everywhere: colour (0.5, 0.25, 0) and opacity a = 0.2 per index unit along a path of 8 index units (the box
  // z ∈ [0, 8]) give A = 1 − (1 − a)^8 and colour C / A = (0.5, 0.25, 0), whatever the step.
  const VolumeSpline s = constant_volume(5.0f);
  const double A = 1.0 - std::pow(0.8, 8.0);
  for (double step : {0.5, 0.3, 1.0, 3.0}) {
    const glm::dvec4 c = dvr_ray(s, ramp(), glm::dvec3(4.0, 4.0, -10.0), glm::dvec3(0.0, 0.0, 2.0), step);
    EXPECT_NEAR(c.w, A, 1e-12) << step;
    EXPECT_NEAR(c.x, srgb(0.5) * A, 1e-12) << step;
    EXPECT_NEAR(c.y, srgb(0.25) * A, 1e-12) << step;
    EXPECT_NEAR(c.z, 0.0, 1e-12) << step;
  }
  // A ray missing the box, and one starting inside it (half the path).
  EXPECT_EQ(dvr_ray(s, ramp(), glm::dvec3(20.0, 4.0, -10.0), glm::dvec3(0.0, 0.0, 1.0)), glm::dvec4(0.0));
  EXPECT_NEAR(dvr_ray(s, ramp(), glm::dvec3(4.0, 4.0, 4.0), glm::dvec3(0.0, 0.0, 1.0)).w, 1.0 - std::pow(0.8, 4.0),
              1e-12);
  // Opaque: the march stops at kDvrOpaque.
  const VolumeSpline dense = constant_volume(20.0f);
  EXPECT_GE(dvr_ray(dense, ramp(), glm::dvec3(4.0, 4.0, -10.0), glm::dvec3(0.0, 0.0, 1.0)).w, kDvrOpaque);
}

TEST(DvrImage, BrickSkippingChangesNoBit) {
  const trispline::test::SphereVolume sphere = trispline::test::sphere_volume({30, 30, 30});
  const VolumeSpline s(sphere.volume, 4, false);
  const glm::dvec3 c = sphere.field.center;
  // Outside the sphere transparent, a shell near its surface orange, the core blue and dense.
  const TransferFunction tf{{{-1.0, {0, 0, 0, 0}}, {0.0, {1.0, 0.5, 0.1, 0.3}}, {4.0, {0.1, 0.3, 1.0, 0.8}}}};
  const glm::dmat4 view = glm::lookAt(c + glm::dvec3(10, 20, 45), c, glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspective(glm::radians(35.0), 1.0, 1.0, 200.0);
  const VolumeRangeGrid grid = build_volume_range_grid(s);
  const DvrImage plain = render_dvr_cpu(s, tf, view, proj, 48, 48, 0.5);
  const DvrImage skipped = render_dvr_cpu(s, tf, view, proj, 48, 48, 0.5, &grid);
  ASSERT_EQ(plain.rgba.size(), 48u * 48u);
  std::size_t seen = 0;
  for (std::size_t i = 0; i < plain.rgba.size(); ++i) {
    EXPECT_EQ(plain.rgba[i], skipped.rgba[i]) << i;
    seen += plain.rgba[i].w > 0.5f;
  }
  EXPECT_GT(seen, 48u * 48u / 10);            // the sphere covers a good part of the view
  EXPECT_EQ(plain.rgba[0], glm::vec4(0.0f));  // a corner sees only air
  EXPECT_THROW(render_dvr_cpu(s, tf, view, proj, 0, 4), std::invalid_argument);
}
