#include "bench/silhouette_bench.h"

#include <sys/resource.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unordered_map>

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

// The fraction of `full`'s visible points within `tol_mm` of a visible point of `r` (1 when `full` has none).
double visible_coverage(const SilhouetteResult& full, const SilhouetteResult& r, double tol_mm) {
  std::unordered_map<std::uint64_t, std::vector<glm::dvec3>> grid;
  auto key = [&](const glm::ivec3& c) {
    return (std::uint64_t(std::uint32_t(c.x)) * 0x9E3779B97F4A7C15ull) ^
           (std::uint64_t(std::uint32_t(c.y)) * 0xC2B2AE3D27D4EB4Full) ^
           (std::uint64_t(std::uint32_t(c.z)) * 0x165667B19E3779F9ull);
  };
  auto cell = [&](const glm::dvec3& x) { return glm::ivec3(glm::floor(x / tol_mm)); };
  for (const SilhouettePolyline& pl : r.polylines)
    for (std::size_t i = 0; i < pl.points.size(); ++i)
      if (pl.visible[i]) grid[key(cell(pl.points[i]))].push_back(pl.points[i]);
  std::size_t seen = 0, found = 0;
  for (const SilhouettePolyline& pl : full.polylines)
    for (std::size_t i = 0; i < pl.points.size(); ++i) {
      if (!pl.visible[i]) continue;
      ++seen;
      const glm::ivec3 c = cell(pl.points[i]);
      bool near = false;
      for (int dz = -1; dz <= 1 && !near; ++dz)
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx)
            if (const auto it = grid.find(key(c + glm::ivec3(dx, dy, dz))); it != grid.end())
              for (const glm::dvec3& y : it->second)
                if (glm::length(y - pl.points[i]) <= tol_mm) {
                  near = true;
                  break;
                }
      found += near;
    }
  return seen ? double(found) / double(seen) : 1.0;
}

template <class T>
T median(std::vector<T> v) {
  if (v.empty()) return T{};
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The benchmark's volume: "analytic:sphere|torus|sines" sampled 96 to an axis, else the file or folder load_volume
// reads.
ScalarVolume load_silhouette_bench_volume(const std::string& path) {
  AnalyticVolume kind;
  const std::string prefix = "analytic:";
  if (path.rfind(prefix, 0) == 0 && parse_analytic_volume(path.substr(prefix.size()), kind))
    return make_analytic_volume(kind, 96);
  return load_volume(path);
}

// The circle the views' eyes lie on: about the volume's z axis through its centre, 20° above its equator, at 2.2×
// its half-diagonal from the centre (world millimetres).
struct SilhouetteBenchCircle {
  glm::dvec3 centre{0.0};
  double radius = 0.0;                                                        // half the diagonal, mm
  static constexpr double elevation = 20.0 * 3.14159265358979323846 / 180.0;  // radians

  // The eye at azimuth `az` (radians).
  glm::dvec3 eye(double az) const {
    return centre +
           2.2 * radius *
               glm::dvec3(std::cos(elevation) * std::cos(az), std::cos(elevation) * std::sin(az), std::sin(elevation));
  }
};

// The circle of `volume`: its index-space centre and half the distance between its first and last samples, in world
// millimetres.
SilhouetteBenchCircle silhouette_bench_circle(const ScalarVolume& volume) {
  const glm::dvec3 hi(volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1);
  SilhouetteBenchCircle circle;
  circle.centre = volume.world(hi * 0.5);
  circle.radius = 0.5 * glm::length(volume.world(hi) - volume.world(glm::dvec3(0.0)));
  return circle;
}

// The figures of the `views` evenly spaced views: per view, and the series the summary takes medians of.
struct SilhouetteBenchViews {
  nlohmann::json per_view = nlohmann::json::array();
  std::vector<double> view_ms, extract_ms, hidden_ms, length;  // ms, ms, ms, mm
  std::vector<std::size_t> points, candidates, seeds;
  double max_value = 0.0, max_dot = 0.0;  // the largest Newton residuals over all views
};

// Extracts the silhouettes of every evenly spaced view (no screen: pixel_size 0), one after another.
SilhouetteBenchViews time_silhouette_views(const VolumeSpline& spline, const SingletonTable& table,
                                           const SilhouetteBenchOptions& o, const SilhouetteBenchCircle& circle,
                                           const SilhouetteParams& params) {
  SilhouetteBenchViews f;
  for (int v = 0; v < o.views; ++v) {
    const double az = 2.0 * 3.14159265358979323846 * v / o.views;
    SilhouetteView view;
    view.eye = circle.eye(az);
    const SilhouetteResult r = extract_silhouettes(spline, table, o.iso, view, params);
    f.view_ms.push_back(r.extract_ms + r.hidden_ms);
    f.extract_ms.push_back(r.extract_ms);
    f.hidden_ms.push_back(r.hidden_ms);
    f.points.push_back(r.points);
    f.candidates.push_back(r.candidates);
    f.seeds.push_back(r.seeds);
    f.length.push_back(r.length_mm);
    f.max_value = std::max(f.max_value, r.max_value_residual);
    f.max_dot = std::max(f.max_dot, r.max_dot_residual);
    f.per_view.push_back({{"azimuth_deg", az * 180.0 / 3.14159265358979323846},
                          {"extract_ms", r.extract_ms},
                          {"hidden_ms", r.hidden_ms},
                          {"candidates", r.candidates},
                          {"seeds", r.seeds},
                          {"points", r.points},
                          {"polylines", r.polylines.size()},
                          {"length_mm", r.length_mm}});
  }
  return f;
}

// Orbit view `v` (0…35): azimuth 10·v degrees on the circle, at the pixel density of a 1280 × 720 viewport with a
// 45° field of view.
SilhouetteView silhouette_orbit_view(const SilhouetteBenchCircle& circle, int v) {
  const double az = 10.0 * v * 3.14159265358979323846 / 180.0;
  SilhouetteView view;
  view.eye = circle.eye(az);
  view.pixel_size = 2.0 * std::tan(22.5 * 3.14159265358979323846 / 180.0) / 720.0;
  return view;
}

// The orbit's results and figures, per view in orbit order: time (ms), points, visible points and its JSON row.
struct SilhouetteOrbitRun {
  std::vector<SilhouetteResult> results;
  std::vector<double> ms;
  std::vector<std::size_t> pts, visible_pts;
  nlohmann::json views = nlohmann::json::array();
};

// The 36 orbit views through `sequence`, timed alone (as the editor runs it).
SilhouetteOrbitRun run_silhouette_orbit_views(SilhouetteSequence& sequence, double iso, const SilhouetteParams& editor,
                                              const SilhouetteBenchCircle& circle) {
  SilhouetteOrbitRun run;
  for (int v = 0; v < 36; ++v) {
    run.results.push_back(sequence.next(iso, silhouette_orbit_view(circle, v), editor));
    const SilhouetteResult& r = run.results.back();
    std::size_t seen = 0;
    for (const SilhouettePolyline& pl : r.polylines)
      for (unsigned char f : pl.visible) seen += f;
    run.ms.push_back(r.extract_ms + r.hidden_ms);
    run.pts.push_back(r.points);
    run.visible_pts.push_back(seen);
    run.views.push_back({{"azimuth_deg", 10.0 * v},
                         {"view_ms", run.ms.back()},
                         {"extract_ms", r.extract_ms},
                         {"hidden_ms", r.hidden_ms},
                         {"points", r.points},
                         {"visible_points", seen},
                         {"polylines", r.polylines.size()},
                         {"traced_from_previous", r.traced_from_previous},
                         {"candidates", r.candidates},
                         {"seeds", r.seeds},
                         {"hidden_cells", r.hidden_cells}});
  }
  return run;
}

// Per orbit view, the share of the full extraction's visible points (`full`: no sequence, no screen) found by the
// orbit's view, also written as the view row's "coverage". Found: within a cell (`cell_mm`) and 2 pixels (at the
// volume's centre) of a visible point of the orbit's view.
std::vector<double> silhouette_orbit_coverage(const VolumeSpline& spline, const SingletonTable& table, double iso,
                                              const SilhouetteParams& full, const SilhouetteBenchCircle& circle,
                                              double cell_mm, SilhouetteOrbitRun& run) {
  std::vector<double> coverage;
  for (int v = 0; v < 36; ++v) {
    SilhouetteView whole = silhouette_orbit_view(circle, v);
    const double tol_mm = cell_mm + 2.0 * whole.pixel_size * glm::length(circle.centre - whole.eye);
    whole.pixel_size = 0.0;
    coverage.push_back(visible_coverage(extract_silhouettes(spline, table, iso, whole, full), run.results[v], tol_mm));
    run.views[v]["coverage"] = coverage.back();
  }
  return coverage;
}

// As the editor's live view: a SilhouetteSequence, hidden cells seeding nothing, the density of a 1280 × 720
// viewport at a 45° field of view. Each view is checked against the full extraction of the same view (no sequence,
// no screen): the visible length the sequence finds over the visible length there is. Returns the orbit_* figures.
nlohmann::json run_silhouette_orbit(const VolumeSpline& spline, const SingletonTable& table, const ScalarVolume& volume,
                                    double iso, const SilhouetteParams& params, const SilhouetteBenchCircle& circle) {
  SilhouetteParams editor = params;
  editor.hidden_test = true;
  editor.seed_hidden = false;
  double cell_mm = 0.0;
  for (int a = 0; a < 3; ++a) cell_mm = std::max(cell_mm, glm::length(glm::dvec3(volume.index_to_world[a])));
  SilhouetteParams full = editor;
  full.pixel_step = 0.0;
  SilhouetteSequence sequence(std::shared_ptr<const VolumeSpline>(&spline, [](const VolumeSpline*) {}),
                              std::shared_ptr<const SingletonTable>(&table, [](const SingletonTable*) {}));
  // The orbit first, timed alone (as the editor runs it), then the full extractions it is checked against.
  SilhouetteOrbitRun run = run_silhouette_orbit_views(sequence, iso, editor, circle);
  const std::vector<double> coverage = silhouette_orbit_coverage(spline, table, iso, full, circle, cell_mm, run);
  return {{"orbit_median_view_ms", median(run.ms)},
          {"orbit_max_view_ms", *std::max_element(run.ms.begin(), run.ms.end())},
          {"orbit_points_per_view", median(run.pts)},
          {"orbit_visible_points_per_view", median(run.visible_pts)},
          {"orbit_median_coverage", median(coverage)},
          {"orbit_min_coverage", *std::min_element(coverage.begin(), coverage.end())},
          {"orbit_views", run.views}};
}

}  // namespace

namespace {

// One camera of the views file (SilhouetteBenchOptions::views_out).
nlohmann::json silhouette_view_camera(const std::string& name, double azimuth_deg, const glm::dvec3& eye,
                                      const SilhouetteBenchCircle& circle) {
  return {{"name", name},
          {"azimuth_deg", azimuth_deg},
          {"eye", {eye.x, eye.y, eye.z}},
          {"target", {circle.centre.x, circle.centre.y, circle.centre.z}},
          {"up", {0.0, 0.0, 1.0}},
          {"fov_deg", 45.0},
          {"viewport", {1280, 720}},
          {"projection", "perspective"}};
}

// Writes the cameras of the timed views (and of the orbit's) to `path`, through "<path>.tmp" and a rename. Throws
// std::runtime_error naming the file when it cannot be written.
void write_silhouette_views(const std::filesystem::path& path, const SilhouetteBenchOptions& o,
                            const SilhouetteBenchCircle& circle) {
  nlohmann::json views = nlohmann::json::array(), orbit = nlohmann::json::array();
  for (int v = 0; v < o.views; ++v) {
    const double az = 2.0 * 3.14159265358979323846 * v / o.views;
    views.push_back(silhouette_view_camera("view_" + std::to_string(v), az * 180.0 / 3.14159265358979323846,
                                           circle.eye(az), circle));
  }
  if (o.orbit)
    for (int v = 0; v < 36; ++v)
      orbit.push_back(
          silhouette_view_camera("orbit_" + std::to_string(v), 10.0 * v, silhouette_orbit_view(circle, v).eye, circle));
  nlohmann::json out = {{"frame", "world millimetres of the volume file's own axes; up is the circle's axis"},
                        {"volume", o.volume_path},
                        {"views", views}};
  if (o.orbit) out["orbit_views"] = orbit;
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << out.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write the views file " + tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write the views file " + path.string());
  }
}

}  // namespace

nlohmann::json run_silhouette_benchmark(const SilhouetteBenchOptions& o) {
  if (o.views < 1) throw std::invalid_argument("--views must be at least 1");
  auto t0 = std::chrono::steady_clock::now();
  const ScalarVolume volume = load_silhouette_bench_volume(o.volume_path);
  const double load_s = seconds_since(t0);
  const VolumeSpline spline(volume, o.order);
  t0 = std::chrono::steady_clock::now();
  const SingletonTable table = build_singleton_table(spline);
  const double prep_s = seconds_since(t0);
  const double prep_rss = peak_rss_mb();

  const SilhouetteBenchCircle circle = silhouette_bench_circle(volume);
  if (!o.views_out.empty()) write_silhouette_views(o.views_out, o, circle);
  SilhouetteParams params;
  params.subdivision = o.subdivision;
  params.accuracy = o.accuracy;
  params.hidden_test = o.hidden;
  const SilhouetteBenchViews f = time_silhouette_views(spline, table, o, circle, params);
  nlohmann::json orbit;
  if (o.orbit) orbit = run_silhouette_orbit(spline, table, volume, o.iso, params, circle);
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
                        {"median_view_ms", median(f.view_ms)},
                        {"max_view_ms", *std::max_element(f.view_ms.begin(), f.view_ms.end())},
                        {"median_extract_ms", median(f.extract_ms)},
                        {"median_hidden_ms", median(f.hidden_ms)},
                        {"points_per_view", median(f.points)},
                        {"candidates_per_view", median(f.candidates)},
                        {"seeds_per_view", median(f.seeds)},
                        {"length_mm_per_view", median(f.length)},
                        {"max_value_residual", f.max_value},
                        {"max_dot_residual", f.max_dot},
                        {"per_view", f.per_view}};
  if (o.orbit) out.update(orbit);
  if (!o.views_out.empty()) out["views_out"] = o.views_out;
  return out;
}

}  // namespace trispline::core
