#include "core/volume/prepared_volume.h"

#include <algorithm>
#include <chrono>
#include <list>
#include <mutex>

#include "core/volume/analytic_volumes.h"

namespace trispline::core {

namespace {

struct Key {
  std::string path;
  std::uintmax_t size = 0;
  std::int64_t mtime = 0;
  int order = 0;
  bool interpolate = false;
  bool superior_up = false;
  bool operator==(const Key& o) const {
    return path == o.path && size == o.size && mtime == o.mtime && order == o.order && interpolate == o.interpolate &&
           superior_up == o.superior_up;
  }
};

std::mutex cache_mutex;
std::list<std::pair<Key, PreparedVolume>> cache;  // most recent first
constexpr std::size_t kCacheEntries = 3;

// Bytes a prepared volume holds: control points and singleton table.
std::uint64_t held_bytes(const PreparedVolume& v) {
  return v.spline->control_points().size() * sizeof(float) + v.table->memory_bytes();
}

Key key_of(const std::filesystem::path& path, int order, bool interpolate) {
  Key k;
  k.path = path.string();
  k.order = order;
  k.interpolate = interpolate;
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) k.size = std::filesystem::file_size(path, ec);
  const auto t = std::filesystem::last_write_time(path, ec);
  if (!ec) k.mtime = t.time_since_epoch().count();
  return k;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

VolumeLoadOptions preparation_load_options() {
  VolumeLoadOptions options;
  options.memory_budget_bytes = kPreparedVolumeBudget;
  options.extra_bytes_per_voxel = kPreparationBytesPerVoxel;
  return options;
}

glm::dmat4 superior_up_rotation(const std::string& frame) {
  glm::dmat4 r(1.0);
  if (frame == "RAS") {  // (x, y, z) → (−x, z, y)
    r[0] = glm::dvec4(-1, 0, 0, 0), r[1] = glm::dvec4(0, 0, 1, 0), r[2] = glm::dvec4(0, 1, 0, 0);
  } else if (frame == "LPS") {  // L = −R, P = −A: (x, y, z) → (x, z, −y)
    r[0] = glm::dvec4(1, 0, 0, 0), r[1] = glm::dvec4(0, 0, -1, 0), r[2] = glm::dvec4(0, 1, 0, 0);
  }
  return r;
}

PreparedVolume prepare_volume(const std::filesystem::path& path, int order, bool interpolate,
                              const ProgressSink& progress, bool superior_up) {
  if (order < 2 || order > 4)
    throw std::invalid_argument("volume spline order must be 2, 3 or 4 (degree + 1), got " + std::to_string(order));
  Key key = key_of(path, order, interpolate);
  key.superior_up = superior_up;
  {
    std::lock_guard<std::mutex> lock(cache_mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it)
      if (it->first == key) {
        cache.splice(cache.begin(), cache, it);
        return cache.front().second;
      }
  }
  PreparedVolume out;
  auto t0 = std::chrono::steady_clock::now();
  ScalarVolume volume;
  AnalyticVolume kind;
  const std::string name = path.string(), prefix = "analytic:";
  if (name.rfind(prefix, 0) == 0 && parse_analytic_volume(name.substr(prefix.size()), kind))
    volume = make_analytic_volume(kind, 96);
  else
    volume = load_volume(path, preparation_load_options());
  out.load_ms = ms_since(t0);
  progress.check(0.0);
  t0 = std::chrono::steady_clock::now();
  // Samples, control points and the table, from the dimensions and order, before the spline is made.
  check_preparation_budget(path.string(), {volume.dims[0], volume.dims[1], volume.dims[2]}, order);
  out.units = volume.units, out.modality = volume.modality, out.source = volume.source, out.frame = volume.frame;
  if (superior_up && !volume.frame.empty()) {
    volume.index_to_world = superior_up_rotation(volume.frame) * volume.index_to_world;
    out.superior_up = true;
  }
  out.default_iso = default_iso_level(volume);
  auto spline = std::make_shared<const VolumeSpline>(volume, order, interpolate);
  std::vector<float>().swap(volume.values);  // freed (not only cleared): the spline holds its own control points
  out.table = std::make_shared<const SingletonTable>(build_singleton_table(*spline, progress));
  out.spline = std::move(spline);
  out.prep_ms = ms_since(t0);
  std::lock_guard<std::mutex> lock(cache_mutex);
  cache.emplace_front(key, out);
  // At most three, and the older ones only while all together stay within one preparation budget.
  std::uint64_t total = 0;
  std::size_t kept = 0;
  for (auto it = cache.begin(); it != cache.end();) {
    const std::uint64_t bytes = held_bytes(it->second);
    if (kept == 0 || (kept < kCacheEntries && total + bytes <= kPreparedVolumeBudget)) {
      total += bytes, ++kept, ++it;
    } else {
      it = cache.erase(it);
    }
  }
  return out;
}

void clear_prepared_volumes() {
  std::lock_guard<std::mutex> lock(cache_mutex);
  cache.clear();
}

double default_iso_level(const ScalarVolume& volume) {
  if (volume.units == "HU") return 226.0;
  const auto [lo_it, hi_it] = std::minmax_element(volume.values.begin(), volume.values.end());
  const double lo = *lo_it, hi = *hi_it;
  if (!(hi > lo)) return lo;
  constexpr int bins = 256;
  std::vector<double> hist(bins, 0.0);
  for (float v : volume.values) ++hist[std::min(bins - 1, static_cast<int>((v - lo) / (hi - lo) * bins))];
  const double total = static_cast<double>(volume.values.size());
  double sum_all = 0.0;
  for (int i = 0; i < bins; ++i) sum_all += i * hist[i];
  // Between-class variance per threshold; where several thresholds share the maximum (empty bins between two
  // classes), the middle of that plateau.
  std::vector<double> between(bins - 1, -1.0);
  double w0 = 0.0, sum0 = 0.0, best = -1.0;
  for (int i = 0; i < bins - 1; ++i) {
    w0 += hist[i], sum0 += i * hist[i];
    const double w1 = total - w0;
    if (w0 == 0.0 || w1 == 0.0) continue;
    const double m0 = sum0 / w0, m1 = (sum_all - sum0) / w1;
    between[i] = w0 * w1 * (m0 - m1) * (m0 - m1);
    best = std::max(best, between[i]);
  }
  int first = -1, last = -1;
  for (int i = 0; i < bins - 1; ++i)
    if (between[i] >= best * (1.0 - 1e-12) && best > 0.0) {
      if (first < 0) first = i;
      last = i;
    }
  if (first < 0) return 0.5 * (lo + hi);
  return lo + (hi - lo) * (0.5 * (first + last) + 1.0) / bins;
}

}  // namespace trispline::core
