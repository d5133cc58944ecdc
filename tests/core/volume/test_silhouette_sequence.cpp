// Silhouettes over a run of nearby views (SilhouetteSequence, the editor's orbit) on a real T1 MRI
// (insighttoolkit5-examples, 128×128×62): seeded from the previous view's curves, at a screen's density, the visible
// curves are those of the complete extraction of each view — every visible point of it lies within a voxel and two
// pixels of a visible point of the sequence's — with fewer points, every point still converged, and the same run of
// views gives the same curves.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_io.h"
#include "core/volume/volume_spline.h"
#include "tests/core/volume/silhouette_coverage.h"

namespace trispline::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

using test::covered;
using test::visible_points;

class SilhouetteSequenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    volume_ = std::make_shared<ScalarVolume>(
        load_volume(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/KmeansTest_T1UCharRaw.nii.gz"));
    spline_ = std::make_shared<const VolumeSpline>(*volume_, 4);
    table_ = std::make_shared<const SingletonTable>(build_singleton_table(*spline_));
  }
  static void TearDownTestSuite() { volume_.reset(), spline_.reset(), table_.reset(); }

  // View k of an orbit 10° a step, 20° above the equator at 2.2 half-diagonals, on a 720-pixel-high 45° screen.
  static SilhouetteView orbit_view(int k) {
    const glm::dvec3 hi(volume_->dims[0] - 1, volume_->dims[1] - 1, volume_->dims[2] - 1);
    const glm::dvec3 centre = volume_->world(0.5 * hi);
    const double radius = 0.5 * glm::length(volume_->world(hi) - volume_->world(glm::dvec3(0.0)));
    const double az = 10.0 * k * kPi / 180.0, el = 20.0 * kPi / 180.0;
    SilhouetteView view;
    view.eye =
        centre + 2.2 * radius * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    view.pixel_size = 2.0 * std::tan(22.5 * kPi / 180.0) / 720.0;
    return view;
  }

  static SilhouetteParams live_params() {
    SilhouetteParams p;
    p.seed_hidden = false;  // the editor's live view with Hidden lines "remove"
    return p;
  }

  static constexpr double kIso = 46.8;
  static inline std::shared_ptr<ScalarVolume> volume_;
  static inline std::shared_ptr<const VolumeSpline> spline_;
  static inline std::shared_ptr<const SingletonTable> table_;
};

TEST_F(SilhouetteSequenceTest, AnOrbitFindsTheVisibleCurvesOfEachViewWithFewerPoints) {
  SilhouetteSequence sequence(spline_, table_);
  const SilhouetteParams params = live_params();
  const double voxel = glm::length(glm::dvec3(volume_->index_to_world[0]));
  std::size_t sequence_points = 0, full_points = 0;
  for (int k = 0; k < 6; ++k) {
    SCOPED_TRACE("view " + std::to_string(k));
    const SilhouetteView view = orbit_view(k);
    const SilhouetteResult r = sequence.next(kIso, view, params);
    SilhouetteView whole = view;
    whole.pixel_size = 0.0;
    SilhouetteParams full_params = params;
    full_params.pixel_step = 0.0;
    const SilhouetteResult full = extract_silhouettes(*spline_, *table_, kIso, whole, full_params);
    ASSERT_GT(visible_points(full).size(), 100u);
    // Within a voxel and two pixels at the eye's distance from the volume.
    const double two_pixels = 2.0 * view.pixel_size * glm::length(volume_->world(glm::dvec3(64, 64, 31)) - view.eye);
    EXPECT_GE(covered(visible_points(full), visible_points(r), voxel + two_pixels), 0.99);
    // Every point the sequence keeps is a converged silhouette point.
    EXPECT_LE(r.max_value_residual, params.accuracy);
    EXPECT_LE(r.max_dot_residual, params.accuracy);
    if (k == 0)
      EXPECT_EQ(r.traced_from_previous, 0u) << "the first view has no previous curves";
    else
      EXPECT_GT(r.traced_from_previous, 0u) << "later views trace from the previous view's curves first";
    sequence_points += r.points;
    full_points += full.points;
  }
  EXPECT_LT(double(sequence_points), 0.7 * double(full_points)) << "the screen's density keeps fewer points";
}

TEST_F(SilhouetteSequenceTest, TheSameRunOfViewsGivesTheSameCurves) {
  SilhouetteSequence a(spline_, table_), b(spline_, table_);
  for (int k = 0; k < 3; ++k) {
    const SilhouetteResult ra = a.next(kIso, orbit_view(k), live_params());
    const SilhouetteResult rb = b.next(kIso, orbit_view(k), live_params());
    ASSERT_EQ(ra.polylines.size(), rb.polylines.size());
    for (std::size_t i = 0; i < ra.polylines.size(); ++i) {
      EXPECT_EQ(ra.polylines[i].points, rb.polylines[i].points);
      EXPECT_EQ(ra.polylines[i].visible, rb.polylines[i].visible);
    }
  }
  // After restart() a sequence starts over: its next view is a fresh sequence's first.
  a.restart();
  SilhouetteSequence fresh(spline_, table_);
  EXPECT_EQ(a.next(kIso, orbit_view(5), live_params()).points, fresh.next(kIso, orbit_view(5), live_params()).points);
}

TEST_F(SilhouetteSequenceTest, BadInputThrowsAndTheRunGoesOn) {
  EXPECT_THROW(SilhouetteSequence(nullptr, table_), std::invalid_argument);
  SilhouetteSequence sequence(spline_, table_);
  const SilhouetteResult first = sequence.next(kIso, orbit_view(0), live_params());
  EXPECT_THROW(sequence.next(std::nan(""), orbit_view(1), live_params()), std::invalid_argument);
  SilhouetteParams bad = live_params();
  bad.pixel_step = -1.0;
  EXPECT_THROW(sequence.next(kIso, orbit_view(1), bad), std::invalid_argument);
  SilhouetteView no_screen = orbit_view(1);
  no_screen.pixel_size = std::nan("");
  EXPECT_THROW(sequence.next(kIso, no_screen, live_params()), std::invalid_argument);
  // The failed calls left the previous view in place.
  EXPECT_GT(sequence.next(kIso, orbit_view(1), live_params()).traced_from_previous, 0u);
  EXPECT_GT(first.points, 0u);
}

}  // namespace
}  // namespace trispline::core
