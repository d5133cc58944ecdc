#include "bench/silhouette_bench.h"

#include <sys/resource.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/volume/analytic_volumes.h"
#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_io.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux: kilobytes
}

template <class T>
T median(std::vector<T> v) {
  if (v.empty()) return T{};
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

nlohmann::json run_silhouette_benchmark(const SilhouetteBenchOptions& o) {
  if (o.views < 1) throw std::invalid_argument("--views must be at least 1");
  auto t0 = std::chrono::steady_clock::now();
  ScalarVolume volume;
  AnalyticVolume kind;
  const std::string prefix = "analytic:";
  if (o.volume_path.rfind(prefix, 0) == 0 && parse_analytic_volume(o.volume_path.substr(prefix.size()), kind))
    volume = make_analytic_volume(kind, 96);
  else
    volume = load_volume(o.volume_path);
  const double load_s = seconds_since(t0);
  const VolumeSpline spline(volume, o.order);
  t0 = std::chrono::steady_clock::now();
  const SingletonTable table = build_singleton_table(spline);
  const double prep_s = seconds_since(t0);
  const double prep_rss = peak_rss_mb();

  const glm::dvec3 hi(volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1);
  const glm::dvec3 centre = volume.world(hi * 0.5);
  const double radius = 0.5 * glm::length(volume.world(hi) - volume.world(glm::dvec3(0.0)));
  SilhouetteParams params;
  params.subdivision = o.subdivision;
  params.accuracy = o.accuracy;
  params.hidden_test = o.hidden;
  nlohmann::json per_view = nlohmann::json::array();
  std::vector<double> view_ms, extract_ms, hidden_ms, length;
  std::vector<std::size_t> points, candidates, seeds;
  double max_value = 0.0, max_dot = 0.0;
  const double elevation = 20.0 * 3.14159265358979323846 / 180.0;
  for (int v = 0; v < o.views; ++v) {
    const double az = 2.0 * 3.14159265358979323846 * v / o.views;
    SilhouetteView view;
    view.eye = centre + 2.2 * radius *
                            glm::dvec3(std::cos(elevation) * std::cos(az), std::cos(elevation) * std::sin(az),
                                       std::sin(elevation));
    const SilhouetteResult r = extract_silhouettes(spline, table, o.iso, view, params);
    view_ms.push_back(r.extract_ms + r.hidden_ms);
    extract_ms.push_back(r.extract_ms);
    hidden_ms.push_back(r.hidden_ms);
    points.push_back(r.points);
    candidates.push_back(r.candidates);
    seeds.push_back(r.seeds);
    length.push_back(r.length_mm);
    max_value = std::max(max_value, r.max_value_residual);
    max_dot = std::max(max_dot, r.max_dot_residual);
    per_view.push_back({{"azimuth_deg", az * 180.0 / 3.14159265358979323846},
                        {"extract_ms", r.extract_ms},
                        {"hidden_ms", r.hidden_ms},
                        {"candidates", r.candidates},
                        {"seeds", r.seeds},
                        {"points", r.points},
                        {"polylines", r.polylines.size()},
                        {"length_mm", r.length_mm}});
  }
  nlohmann::json orbit;
  if (o.orbit) {
    SilhouetteParams editor = params;
    editor.hidden_test = true;
    editor.seed_hidden = false;
    std::vector<double> ms;
    std::vector<std::size_t> pts, visible_pts;
    nlohmann::json views = nlohmann::json::array();
    for (int v = 0; v < 36; ++v) {
      const double az = 10.0 * v * 3.14159265358979323846 / 180.0;
      SilhouetteView view;
      view.eye = centre + 2.2 * radius *
                              glm::dvec3(std::cos(elevation) * std::cos(az), std::cos(elevation) * std::sin(az),
                                         std::sin(elevation));
      const SilhouetteResult r = extract_silhouettes(spline, table, o.iso, view, editor);
      std::size_t seen = 0;
      for (const SilhouettePolyline& pl : r.polylines)
        for (unsigned char f : pl.visible) seen += f;
      ms.push_back(r.extract_ms + r.hidden_ms);
      pts.push_back(r.points);
      visible_pts.push_back(seen);
      views.push_back({{"azimuth_deg", 10.0 * v},
                       {"view_ms", ms.back()},
                       {"points", r.points},
                       {"visible_points", seen},
                       {"polylines", r.polylines.size()},
                       {"hidden_cells", r.hidden_cells}});
    }
    orbit = {{"orbit_median_view_ms", median(ms)},
             {"orbit_max_view_ms", *std::max_element(ms.begin(), ms.end())},
             {"orbit_points_per_view", median(pts)},
             {"orbit_visible_points_per_view", median(visible_pts)},
             {"orbit_views", views}};
  }
  glm::dvec3 spacing;
  for (int a = 0; a < 3; ++a) spacing[a] = glm::length(glm::dvec3(volume.index_to_world[a]));
  nlohmann::json out = {{"bench", "silhouettes"},
                        {"volume", o.volume_path},
                        {"iso", o.iso},
                        {"order", o.order},
                        {"subdivision", o.subdivision},
                        {"accuracy", o.accuracy},
                        {"dims", {volume.dims[0], volume.dims[1], volume.dims[2]}},
                        {"spacing_mm", {spacing.x, spacing.y, spacing.z}},
                        {"threads", tbb::info::default_concurrency()},
                        {"load_s", load_s},
                        {"prep_s", prep_s},
                        {"table_mb", table.memory_bytes() / 1048576.0},
                        {"prep_rss_mb", prep_rss},
                        {"peak_rss_mb", peak_rss_mb()},
                        {"views", o.views},
                        {"median_view_ms", median(view_ms)},
                        {"max_view_ms", *std::max_element(view_ms.begin(), view_ms.end())},
                        {"median_extract_ms", median(extract_ms)},
                        {"median_hidden_ms", median(hidden_ms)},
                        {"points_per_view", median(points)},
                        {"candidates_per_view", median(candidates)},
                        {"seeds_per_view", median(seeds)},
                        {"length_mm_per_view", median(length)},
                        {"max_value_residual", max_value},
                        {"max_dot_residual", max_dot},
                        {"per_view", per_view}};
  if (o.orbit) out.update(orbit);
  return out;
}

}  // namespace trispline::core
