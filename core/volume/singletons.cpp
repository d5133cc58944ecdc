#include "core/volume/singletons.h"

#include "core/volume/bezier_cell.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numeric>

#include <tbb/parallel_for.h>

namespace trispline::core {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Bounds of one cell from its Bézier form: the value range and the cone of the degree-raised gradient coefficients.
template <int K>
Singleton bound_cell(const VolumeSpline& spline, int a, int b, int c) {
  constexpr int n = K * K * K;
  double bez[n];
  spline.bezier_coefficients(a, b, c, bez);
  Singleton s;
  double lo = bez[0], hi = bez[0];
  for (int m = 1; m < n; ++m) lo = std::min(lo, bez[m]), hi = std::max(hi, bez[m]);
  s.lo = static_cast<float>(lo);
  s.hi = static_cast<float>(hi);
  // Round outwards so the float range still holds every double value.
  if (double(s.lo) > lo) s.lo = std::nextafter(s.lo, -INFINITY);
  if (double(s.hi) < hi) s.hi = std::nextafter(s.hi, INFINITY);
  if (!(hi > lo)) return s;  // constant cell: no gradient, whole-sphere cone
  // Gradient coefficients: derivative along one axis (degree p − 1 there), raised back to degree p, so all three
  // components share the K³ Bernstein positions and each position holds a vector.
  double g[3][64];
  bezier_cell::gradient_vectors<K>(bez, g);
  double inv_len[n];
  double sx = 0.0, sy = 0.0, sz = 0.0;
  for (int m = 0; m < n; ++m) {
    const double len2 = g[0][m] * g[0][m] + g[1][m] * g[1][m] + g[2][m] * g[2][m];
    if (!(len2 > 0.0)) return s;  // a zero vector in the hull: any direction
    inv_len[m] = 1.0 / std::sqrt(len2);
    sx += g[0][m] * inv_len[m], sy += g[1][m] * inv_len[m], sz += g[2][m] * inv_len[m];
  }
  const double sum_len = std::sqrt(sx * sx + sy * sy + sz * sz);
  if (!(sum_len > 0.0)) return s;
  sx /= sum_len, sy /= sum_len, sz /= sum_len;
  double cos_min = 1.0;
  for (int m = 0; m < n; ++m)
    cos_min = std::min(cos_min, (sx * g[0][m] + sy * g[1][m] + sz * g[2][m]) * inv_len[m]);
  s.axis[0] = static_cast<float>(sx), s.axis[1] = static_cast<float>(sy), s.axis[2] = static_cast<float>(sz);
  if (cos_min <= 0.0) {
    s.sin_half = 1.0f;  // α ≥ 90°: every plane through the origin meets the cone
  } else {
    // Widen slightly: float storage and the rounding of the test must not lose a direction.
    const double sin_half = std::sqrt(std::max(0.0, 1.0 - cos_min * cos_min));
    s.sin_half = static_cast<float>(std::min(1.0, sin_half * (1.0 + 1e-6) + 1e-6));
  }
  return s;
}

Singleton bound_cell(const VolumeSpline& spline, int a, int b, int c) {
  switch (spline.order()) {
    case 2: return bound_cell<2>(spline, a, b, c);
    case 3: return bound_cell<3>(spline, a, b, c);
    default: return bound_cell<4>(spline, a, b, c);
  }
}

// Half-angle (radians) of a singleton's cone, π when it is the whole sphere.
double half_angle(const Singleton& s) {
  if (s.sin_half >= 1.0f || (s.axis[0] == 0.0f && s.axis[1] == 0.0f && s.axis[2] == 0.0f)) return kPi;
  return std::asin(double(s.sin_half));
}

std::vector<glm::vec3> fibonacci_sphere(int n) {
  std::vector<glm::vec3> out(n);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out[i] = glm::vec3(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)), float(z));
  }
  return out;
}

int nearest_column(const std::vector<glm::vec3>& axes, const glm::vec3& d) {
  int best = 0;
  float best_dot = -2.0f;
  for (int i = 0; i < static_cast<int>(axes.size()); ++i) {
    const float v = glm::dot(axes[i], d);
    if (v > best_dot) best_dot = v, best = i;
  }
  return best;
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0));
}

}  // namespace

SingletonTable build_singleton_table(const VolumeSpline& spline, const ProgressSink& progress, int rows,
                                     int columns) {
  if (rows < 1 || columns < 1) throw std::invalid_argument("singleton table needs at least one row and one column");
  SingletonTable t;
  for (int a = 0; a < 3; ++a) t.cells_[a] = spline.span_count(a);
  const std::size_t slab = static_cast<std::size_t>(t.cells_[0]) * t.cells_[1];
  t.singletons_.resize(slab * t.cells_[2]);
  const int nz = t.cells_[2];
  const int chunk = std::max(1, nz / 50);
  for (int z0 = 0; z0 < nz; z0 += chunk) {
    progress.check(0.95 * double(z0) / nz);
    const int z1 = std::min(nz, z0 + chunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(z0 * slab, z1 * slab, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          const int a = static_cast<int>(i % t.cells_[0]);
                          const int b = static_cast<int>((i / t.cells_[0]) % t.cells_[1]);
                          const int c = static_cast<int>(i / slab);
                          t.singletons_[i] = bound_cell(spline, a, b, c);
                        }
                      });
  }
  progress.check(0.95);
  t.rows_ = rows;
  t.column_axes_ = fibonacci_sphere(columns);
  // Column radius: the largest angle from a sphere point to its nearest axis, measured on a fine Fibonacci set and
  // widened by that set's own spacing (so it bounds every point of the sphere).
  const int probes = 20000;
  const auto probe = fibonacci_sphere(probes);
  double radius = 0.0;
  for (const glm::vec3& d : probe)
    radius = std::max(radius, angle_between(glm::dvec3(d), glm::dvec3(t.column_axes_[nearest_column(t.column_axes_, d)])));
  t.column_radius_ = radius + 2.0 * std::sqrt(4.0 * kPi / probes);
  t.file_bins();
  progress.check(1.0);
  return t;
}

void SingletonTable::file_bins() {
  range_min_ = INFINITY, range_max_ = -INFINITY;
  for (const Singleton& s : singletons_) range_min_ = std::min(range_min_, double(s.lo)), range_max_ = std::max(range_max_, double(s.hi));
  if (singletons_.empty()) range_min_ = range_max_ = 0.0;
  const int cols = columns();
  const std::size_t bins = static_cast<std::size_t>(rows_) * cols;
  const double span = range_max_ - range_min_;
  auto row_of = [&](double v) {
    if (!(span > 0.0)) return 0;
    return std::clamp(static_cast<int>(std::floor((v - range_min_) / span * rows_)), 0, rows_ - 1);
  };
  std::vector<std::uint32_t> bin_of(singletons_.size(), UINT32_MAX);
  std::vector<std::uint32_t> counts(bins, 0);
  bin_half_angle_.assign(bins, 0.0f);
  for (std::size_t i = 0; i < singletons_.size(); ++i) {
    const Singleton& s = singletons_[i];
    if (!(s.hi > s.lo)) continue;  // constant: holds one level, and no silhouette (∇D = 0)
    const glm::vec3 axis(s.axis[0], s.axis[1], s.axis[2]);
    const bool full = half_angle(s) >= kPi;
    const int col = full ? 0 : nearest_column(column_axes_, axis);
    const std::uint32_t bin = static_cast<std::uint32_t>(row_of(s.lo) * cols + col);
    bin_of[i] = bin;
    ++counts[bin];
    const double widened =
        full ? kPi : angle_between(glm::dvec3(axis), glm::dvec3(column_axes_[col])) + half_angle(s) + 1e-6;
    bin_half_angle_[bin] = std::max(bin_half_angle_[bin], static_cast<float>(widened));
  }
  bin_begin_.assign(bins + 1, 0);
  for (std::size_t b = 0; b < bins; ++b) bin_begin_[b + 1] = bin_begin_[b] + counts[b];
  bin_cells_.assign(bin_begin_[bins], 0);
  std::vector<std::uint32_t> fill(bin_begin_.begin(), bin_begin_.end() - 1);
  for (std::size_t i = 0; i < singletons_.size(); ++i)
    if (bin_of[i] != UINT32_MAX) bin_cells_[fill[bin_of[i]]++] = static_cast<std::uint32_t>(i);
  tbb::parallel_for(std::size_t(0), bins, [&](std::size_t b) {
    std::sort(bin_cells_.begin() + bin_begin_[b], bin_cells_.begin() + bin_begin_[b + 1],
              [&](std::uint32_t x, std::uint32_t y) {
                const float hx = singletons_[x].hi, hy = singletons_[y].hi;
                return hx != hy ? hx > hy : x < y;
              });
  });
  // Macro-cells.
  for (int a = 0; a < 3; ++a) macro_dims_[a] = (cells_[a] + kMacro - 1) / kMacro;
  macro_range_.assign(static_cast<std::size_t>(macro_dims_[0]) * macro_dims_[1] * macro_dims_[2],
                      glm::vec2(INFINITY, -INFINITY));
  for (int c = 0; c < cells_[2]; ++c)
    for (int b = 0; b < cells_[1]; ++b)
      for (int a = 0; a < cells_[0]; ++a) {
        const Singleton& s = singletons_[cell_index(a, b, c)];
        glm::vec2& m = macro_range_[static_cast<std::size_t>(a / kMacro) +
                                    static_cast<std::size_t>(macro_dims_[0]) *
                                        (static_cast<std::size_t>(b / kMacro) +
                                         static_cast<std::size_t>(macro_dims_[1]) * (c / kMacro))];
        m.x = std::min(m.x, s.lo), m.y = std::max(m.y, s.hi);
      }
}

namespace {

using CellOrder = SingletonTable::CellOrder;

template <class Keep>
std::vector<std::uint32_t> query(const std::vector<Singleton>& singletons, const std::vector<std::uint32_t>& begin,
                                 const std::vector<std::uint32_t>& cells, int rows, int cols, double range_min,
                                 double range_max, double iso, CellOrder order, Keep keep_bin) {
  std::vector<std::uint32_t> out;
  if (!(iso >= range_min && iso <= range_max)) return out;
  const double span = range_max - range_min;
  const int last_row =
      span > 0.0 ? std::clamp(static_cast<int>(std::floor((iso - range_min) / span * rows)), 0, rows - 1) : 0;
  for (int r = 0; r <= last_row; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::size_t bin = static_cast<std::size_t>(r) * cols + c;
      if (begin[bin] == begin[bin + 1] || !keep_bin(bin, c)) continue;
      // Sorted by hi, largest first: the cells with hi ≥ iso are a prefix. A row below the level's row holds only
      // cells with lo < iso (rows are filed by lo with the same monotone formula), so only the level's row tests lo.
      const auto first = cells.begin() + begin[bin], last = cells.begin() + begin[bin + 1];
      const auto end = std::partition_point(first, last, [&](std::uint32_t cell) { return double(singletons[cell].hi) >= iso; });
      if (r < last_row) {
        out.insert(out.end(), first, end);
      } else {
        for (auto e = first; e != end; ++e)
          if (double(singletons[*e].lo) <= iso) out.push_back(*e);
      }
    }
  if (order == CellOrder::ascending) std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<std::uint32_t> SingletonTable::cells_holding(double iso) const {
  return query(singletons_, bin_begin_, bin_cells_, rows_, columns(), range_min_, range_max_, iso,
               CellOrder::ascending, [](std::size_t, int) { return true; });
}

std::vector<std::uint32_t> SingletonTable::cells_holding(double iso, const glm::dvec3& w_axis, double w_half_angle,
                                                         CellOrder order) const {
  return query(singletons_, bin_begin_, bin_cells_, rows_, columns(), range_min_, range_max_, iso, order,
               [&](std::size_t bin, int col) {
                 const double beta = bin_half_angle_[bin];
                 if (beta + w_half_angle >= kPi / 2) return true;
                 const double theta = angle_between(glm::dvec3(column_axes_[col]), w_axis);
                 return std::abs(theta - kPi / 2) <= beta + w_half_angle;
               });
}

std::size_t SingletonTable::memory_bytes() const {
  return singletons_.size() * sizeof(Singleton) + bin_begin_.size() * 4 + bin_cells_.size() * 4 +
         bin_half_angle_.size() * 4 + macro_range_.size() * sizeof(glm::vec2) + column_axes_.size() * sizeof(glm::vec3);
}

// ---- the on-disk cache ----------------------------------------------------------------------------------------------

std::uint64_t singleton_cache_key(const VolumeSpline& spline) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const std::int32_t head[6] = {spline.dims()[0], spline.dims()[1], spline.dims()[2], spline.order(),
                                spline.interpolating() ? 1 : 0, 1 /* bound_cell version */};
  mix(head, sizeof(head));
  mix(spline.control_points().data(), spline.control_points().size() * sizeof(float));
  return h;
}

std::filesystem::path singleton_cache_dir() {
  if (const char* d = std::getenv("TRISPLINE_CACHE_DIR"); d && *d) return std::filesystem::path(d);
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "trispline" / "volumes";
  if (const char* d = std::getenv("HOME"); d && *d)
    return std::filesystem::path(d) / ".cache" / "trispline" / "volumes";
  return std::filesystem::temp_directory_path() / "trispline-cache" / "volumes";
}

namespace {

constexpr char kMagic[8] = {'T', 'S', 'P', 'L', 'S', 'N', 'G', '1'};

struct CacheHead {
  char magic[8];
  std::uint64_t key;
  std::int32_t cells[3];
  std::int32_t rows, columns, macro[3];
  double range_min, range_max, column_radius;
  std::uint64_t singletons, bin_cells;
};

template <class T>
void put(std::ofstream& f, const std::vector<T>& v) {
  f.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

template <class T>
bool get(std::ifstream& f, std::vector<T>& v, std::uint64_t n) {
  v.resize(n);
  f.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  return static_cast<std::uint64_t>(f.gcount()) == n * sizeof(T);
}

}  // namespace

void write_singleton_cache(const SingletonTable& t, const std::filesystem::path& path, std::uint64_t key) {
  CacheHead h{};
  std::memcpy(h.magic, kMagic, 8);
  h.key = key;
  for (int a = 0; a < 3; ++a) h.cells[a] = t.cells_[a], h.macro[a] = t.macro_dims_[a];
  h.rows = t.rows_;
  h.columns = t.columns();
  h.range_min = t.range_min_, h.range_max = t.range_max_, h.column_radius = t.column_radius_;
  h.singletons = t.singletons_.size();
  h.bin_cells = t.bin_cells_.size();
  std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write the singleton cache " + tmp.string());
    f.write(reinterpret_cast<const char*>(&h), sizeof(h));
    put(f, t.singletons_), put(f, t.column_axes_), put(f, t.bin_begin_), put(f, t.bin_cells_);
    put(f, t.bin_half_angle_), put(f, t.macro_range_);
    if (!f) throw std::runtime_error("cannot write the singleton cache " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

bool read_singleton_cache(const std::filesystem::path& path, std::uint64_t key, SingletonTable& out) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size < sizeof(CacheHead)) return false;
  std::ifstream f(path, std::ios::binary);
  CacheHead h{};
  if (!f.read(reinterpret_cast<char*>(&h), sizeof(h)) || std::memcmp(h.magic, kMagic, 8) != 0 || h.key != key)
    return false;
  for (int a = 0; a < 3; ++a)
    if (h.cells[a] < 1 || h.macro[a] != (h.cells[a] + SingletonTable::kMacro - 1) / SingletonTable::kMacro) return false;
  if (h.rows < 1 || h.rows > (1 << 16) || h.columns < 1 || h.columns > (1 << 16)) return false;
  const std::uint64_t cells = std::uint64_t(h.cells[0]) * h.cells[1] * h.cells[2];
  const std::uint64_t bins = std::uint64_t(h.rows) * h.columns;
  const std::uint64_t macros = std::uint64_t(h.macro[0]) * h.macro[1] * h.macro[2];
  if (h.singletons != cells || h.bin_cells > cells) return false;
  const std::uint64_t expected = sizeof(CacheHead) + cells * sizeof(Singleton) + h.columns * sizeof(glm::vec3) +
                                 (bins + 1) * 4 + h.bin_cells * 4 + bins * 4 + macros * sizeof(glm::vec2);
  if (size != expected) return false;  // sizes checked against the file before anything is allocated
  SingletonTable t;
  for (int a = 0; a < 3; ++a) t.cells_[a] = h.cells[a], t.macro_dims_[a] = h.macro[a];
  t.rows_ = h.rows;
  t.range_min_ = h.range_min, t.range_max_ = h.range_max, t.column_radius_ = h.column_radius;
  if (!get(f, t.singletons_, cells) || !get(f, t.column_axes_, h.columns) || !get(f, t.bin_begin_, bins + 1) ||
      !get(f, t.bin_cells_, h.bin_cells) || !get(f, t.bin_half_angle_, bins) || !get(f, t.macro_range_, macros))
    return false;
  if (t.bin_begin_.front() != 0 || t.bin_begin_.back() != h.bin_cells) return false;
  for (std::uint64_t b = 0; b < bins; ++b)
    if (t.bin_begin_[b] > t.bin_begin_[b + 1]) return false;
  for (std::uint32_t c : t.bin_cells_)
    if (c >= cells) return false;
  out = std::move(t);
  return true;
}

SingletonTable cached_singleton_table(const VolumeSpline& spline, const ProgressSink& progress, bool* from_cache) {
  const std::uint64_t key = singleton_cache_key(spline);
  char name[32];
  std::snprintf(name, sizeof(name), "%016llx.singletons", static_cast<unsigned long long>(key));
  const std::filesystem::path path = singleton_cache_dir() / name;
  SingletonTable t;
  if (read_singleton_cache(path, key, t)) {
    if (from_cache) *from_cache = true;
    progress.check(1.0);
    return t;
  }
  t = build_singleton_table(spline, progress);
  if (from_cache) *from_cache = false;
  try {
    write_singleton_cache(t, path, key);
  } catch (const std::exception&) {
    // The cache is an optimisation: a read-only or full disk only costs the next load its preprocessing.
  }
  return t;
}

}  // namespace trispline::core
