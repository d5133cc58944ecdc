// Seeding only where the iso-surface may be seen (SilhouetteParams::seed_hidden = false, the editor's live view with
// hidden lines removed), on a real T1 MRI (insighttoolkit5-examples, 128×128×62) whose silhouettes are mostly small
// curves inside the head: far fewer points are traced, and the visible curves are the same — every visible point of
// the complete extraction lies within a voxel of a visible point of the culled one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>
#include <vector>

#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_io.h"
#include "core/volume/volume_spline.h"
#include "tests/core/volume/silhouette_coverage.h"

namespace trispline::core {
namespace {

using test::covered;
using test::visible_points;

TEST(SilhouetteHiddenCells, FewerPointsTheSameVisibleCurvesOnARealMri) {
  const ScalarVolume volume =
      load_volume(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/KmeansTest_T1UCharRaw.nii.gz");
  const VolumeSpline spline(volume, 4);
  const SingletonTable table = build_singleton_table(spline);
  const glm::dvec3 hi(volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1);
  const glm::dvec3 centre = volume.world(0.5 * hi);
  const double radius = 0.5 * glm::length(volume.world(hi) - volume.world(glm::dvec3(0.0)));
  const double voxel = glm::length(glm::dvec3(volume.index_to_world[0]));
  SilhouetteParams culled_params;
  culled_params.seed_hidden = false;
  std::size_t all_points = 0, culled_points = 0;
  for (int k = 0; k < 5; ++k) {
    SilhouetteView view;
    const double az = 2.0 * 3.14159265358979323846 * k / 4.0;
    if (k < 4) {
      view.eye = centre + 2.2 * radius * glm::dvec3(0.94 * std::cos(az), 0.94 * std::sin(az), 0.34);
    } else {
      view.perspective = false;
      view.direction = glm::dvec3(-0.3, 1.0, -0.2);
    }
    const SilhouetteResult all = extract_silhouettes(spline, table, 46.8, view);
    const SilhouetteResult culled = extract_silhouettes(spline, table, 46.8, view, culled_params);
    const std::vector<glm::dvec3> seen_all = visible_points(all), seen_culled = visible_points(culled);
    SCOPED_TRACE("view " + std::to_string(k));
    EXPECT_EQ(all.hidden_cells, 0u);
    EXPECT_GT(culled.hidden_cells, 0u);
    EXPECT_LT(culled.points, all.points);
    EXPECT_GT(seen_all.size(), 500u);
    const double kept = covered(seen_all, seen_culled, voxel), same = covered(seen_culled, seen_all, voxel);
    std::printf("[hidden cells] view %d: %zu / %zu points, %zu / %zu visible, %.4f kept, %.4f the same\n", k,
                culled.points, all.points, seen_culled.size(), seen_all.size(), kept, same);
    EXPECT_GE(kept, 0.99);
    EXPECT_GE(same, 0.99);
    all_points += all.points, culled_points += culled.points;
  }
  std::printf("[hidden cells] %zu points traced instead of %zu over 5 views\n", culled_points, all_points);
  EXPECT_LT(culled_points, all_points / 2);

  // With the eye inside the grid box there is no map: every cell seeds.
  SilhouetteView inside;
  inside.eye = centre;
  const SilhouetteResult r = extract_silhouettes(spline, table, 46.8, inside, culled_params);
  EXPECT_EQ(r.hidden_cells, 0u);
  EXPECT_EQ(r.points, extract_silhouettes(spline, table, 46.8, inside).points);
}

}  // namespace
}  // namespace trispline::core
