// trispline::core silhouette benchmark — the figures behind `trispline bench silhouettes` (docs/performance.md).
//
// Loads a volume (default: InVesalius' Cranium CT, assets/data/Cranium.inv3, at 226 HU), makes the tri-cubic spline
// D (control points = the samples, seed §7.3.1), preprocesses its singletons and lookup table (timed; the
// process's peak resident memory after it and after the views), then extracts the silhouettes of D = iso for `views`
// perspective views evenly spaced on a circle around the volume (about its z axis, 20° above its equator, at 2.2×
// its half-diagonal from its centre; the views' up is +z) — per view the milliseconds of the extraction (candidates,
// Newton, polylines) and of the hidden-line test, the points, the polyline length and the Newton residuals. Prints
// figures; never asserts timings. Source: seed §7.4 (the seed's own figures are quoted in docs/performance.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace trispline::core {

struct SilhouetteBenchOptions {
  std::string volume_path = "assets/data/Cranium.inv3";  // anything load_volume reads, or analytic:sphere|torus|sines
  double iso = 226.0;                                    // the volume's units (HU for the Cranium)
  int views = 36;                                        // ≥ 1
  int order = 4;                                         // 2…4
  int subdivision = 1;                                   // SilhouetteParams::subdivision
  double accuracy = 1e-7;                                // SilhouetteParams::accuracy
  bool hidden = true;                                    // time the hidden-line test too
  // Also orbit as the editor does with Hidden lines "remove": 36 views 10° apart on the same circle as one
  // SilhouetteSequence (each view seeded from the previous one's curves), hidden cells seeding nothing, at the density
  // of a 1280 × 720 screen with a 45° field of view; then each view's complete extraction, to check the coverage.
  bool orbit = false;
  // A JSON file to write the exact cameras of the views to, so that a peer renders the same ones ("" = none):
  // {"frame", "views":[{"name", "azimuth_deg", "eye", "target", "up", "fov_deg", "viewport", "projection"}],
  //  "orbit_views":[…] with `orbit`}; eye and target in world millimetres of the volume file's own frame, up +z
  // (the circle's axis), fov_deg 45 and viewport [1280, 720] (the orbit's screen density; the timed views have no
  // screen, and their silhouettes do not depend on the field of view).
  std::string views_out;
};

// Result: {bench:"silhouettes", volume, iso, order, dims [nx,ny,nz], spacing_mm [..], threads, load_s, prep_s,
//          table_mb, peak_rss_mb, views, median_view_ms, max_view_ms, median_extract_ms, median_hidden_ms,
//          points_per_view (median), candidates_per_view (median), seeds_per_view (median), length_mm_per_view
//          (median), max_value_residual, max_dot_residual, per_view [{azimuth_deg, extract_ms, hidden_ms, points,
//          polylines, length_mm}]}; with `orbit` also orbit_median_view_ms, orbit_max_view_ms,
//          orbit_points_per_view, orbit_visible_points_per_view (medians), orbit_median_coverage and
//          orbit_min_coverage (the share of the complete extraction's visible points within a cell and 2 pixels of a
//          visible point of the orbit's view) and orbit_views [{azimuth_deg, view_ms, extract_ms, hidden_ms, points,
//          visible_points, polylines, traced_from_previous, candidates, seeds, hidden_cells, coverage}]. peak_rss_mb:
//          the process's peak after the last view; prep_rss_mb: after preprocessing. With `views_out`, also
//          views_out (the file written before the first view).
// Throws std::invalid_argument on bad options, what load_volume throws on a bad file, and std::runtime_error when
// the views file cannot be written.
nlohmann::json run_silhouette_benchmark(const SilhouetteBenchOptions& options);

}  // namespace trispline::core
