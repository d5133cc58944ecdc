#include "core/volume/singletons.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <utility>

#include "core/volume/bezier_cell.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace trispline::core {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Bounds of one cell from its Bézier form: the value range and the cone of the degree-raised gradient coefficients.
template <int K>
Singleton bound_bezier(const double* bez) {
  constexpr int n = K * K * K;
  constexpr int padded = (n + 3) / 4 * 4;  // whole groups of four for the vector loops
  Singleton s;
  double lo = bez[0], hi = bez[0];
  int m0 = 1;
#if defined(__SSE2__)
  {  // four independent minimum and maximum chains instead of one long one
    __m128d lo2[2] = {_mm_set1_pd(lo), _mm_set1_pd(lo)}, hi2[2] = {lo2[0], lo2[0]};
    for (m0 = 0; m0 + 4 <= n; m0 += 4) {
      const __m128d v0 = _mm_loadu_pd(bez + m0), v1 = _mm_loadu_pd(bez + m0 + 2);
      lo2[0] = _mm_min_pd(lo2[0], v0), lo2[1] = _mm_min_pd(lo2[1], v1);
      hi2[0] = _mm_max_pd(hi2[0], v0), hi2[1] = _mm_max_pd(hi2[1], v1);
    }
    alignas(16) double low[2], high[2];
    _mm_store_pd(low, _mm_min_pd(lo2[0], lo2[1]));
    _mm_store_pd(high, _mm_max_pd(hi2[0], hi2[1]));
    lo = std::min(low[0], low[1]), hi = std::max(high[0], high[1]);
  }
#endif
  for (int m = m0; m < n; ++m) lo = std::min(lo, bez[m]), hi = std::max(hi, bez[m]);
  s.lo = static_cast<float>(lo);
  s.hi = static_cast<float>(hi);
  // Round outwards so the float range still holds every double value.
  if (double(s.lo) > lo) s.lo = std::nextafter(s.lo, -INFINITY);
  if (double(s.hi) < hi) s.hi = std::nextafter(s.hi, INFINITY);
  if (!(hi > lo)) return s;  // constant cell: no gradient, whole-sphere cone
  // Gradient coefficients: derivative along one axis (degree p − 1 there), raised back to degree p, so all three
  // components share the K³ Bernstein positions and each position holds a vector. The padding repeats vector 0 (it
  // changes neither the hull nor its cone).
  alignas(16) double g[3][64];
  bezier_cell::gradient_vectors<K>(bez, g);
  alignas(16) double len2[64];
  for (int m = 0; m < n; ++m) len2[m] = g[0][m] * g[0][m] + g[1][m] * g[1][m] + g[2][m] * g[2][m];
  for (int m = n; m < padded; ++m) g[0][m] = g[0][0], g[1][m] = g[1][0], g[2][m] = g[2][0], len2[m] = len2[0];
  for (int m = 0; m < n; ++m)
    if (!(len2[m] > 0.0)) return s;  // a zero vector in the hull (or a non-finite one): any direction
  // The cone's axis: the sum of the vectors scaled to about unit length. Any axis gives a valid cone — its width is
  // measured against the axis exactly below — so the weights are float reciprocal square roots, four at a time (the
  // double ones took most of a cell's time); IEEE sqrt and division, so every machine files the same axis.
  double sum[3] = {0.0, 0.0, 0.0};
#if defined(__SSE2__)
  __m128d acc[3] = {_mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd()};
  const __m128 one = _mm_set1_ps(1.0f);
  for (int m = 0; m < padded; m += 4) {
    const __m128 l = _mm_movelh_ps(_mm_cvtpd_ps(_mm_load_pd(len2 + m)), _mm_cvtpd_ps(_mm_load_pd(len2 + m + 2)));
    const __m128 w = _mm_div_ps(one, _mm_sqrt_ps(l));
    const __m128d w01 = _mm_cvtps_pd(w), w23 = _mm_cvtps_pd(_mm_movehl_ps(w, w));
    for (int axis = 0; axis < 3; ++axis) {
      acc[axis] = _mm_add_pd(acc[axis], _mm_mul_pd(_mm_load_pd(g[axis] + m), w01));
      acc[axis] = _mm_add_pd(acc[axis], _mm_mul_pd(_mm_load_pd(g[axis] + m + 2), w23));
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    alignas(16) double pair[2];
    _mm_store_pd(pair, acc[axis]);
    sum[axis] = pair[0] + pair[1];
  }
#else
  for (int m = 0; m < padded; ++m) {
    const double w = 1.0f / std::sqrt(static_cast<float>(len2[m]));
    for (int axis = 0; axis < 3; ++axis) sum[axis] += g[axis][m] * w;
  }
#endif
  const double sum_len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  if (!(sum_len > 0.0) || !std::isfinite(sum_len)) return s;  // no usable axis: the whole sphere is still a bound
  const double sx = sum[0] / sum_len, sy = sum[1] / sum_len, sz = sum[2] / sum_len;
  // Width: cos α = min over m of (axis·g_m) / |g_m|. When every dot is positive that is the square root of the least
  // dot² / |g_m|², so the loop needs no square root; any dot ≤ 0 means α ≥ 90°.
  double min_dot = INFINITY, min_cos2 = INFINITY;
#if defined(__SSE2__)
  const __m128d ax = _mm_set1_pd(sx), ay = _mm_set1_pd(sy), az = _mm_set1_pd(sz);
  __m128d dot_lo = _mm_set1_pd(INFINITY), cos2_lo = _mm_set1_pd(INFINITY);
  for (int m = 0; m < padded; m += 2) {
    const __m128d d =
        _mm_add_pd(_mm_add_pd(_mm_mul_pd(ax, _mm_load_pd(g[0] + m)), _mm_mul_pd(ay, _mm_load_pd(g[1] + m))),
                   _mm_mul_pd(az, _mm_load_pd(g[2] + m)));
    dot_lo = _mm_min_pd(dot_lo, d);
    cos2_lo = _mm_min_pd(cos2_lo, _mm_div_pd(_mm_mul_pd(d, d), _mm_load_pd(len2 + m)));
  }
  alignas(16) double pair[2];
  _mm_store_pd(pair, dot_lo);
  min_dot = std::min(pair[0], pair[1]);
  _mm_store_pd(pair, cos2_lo);
  min_cos2 = std::min(pair[0], pair[1]);
#else
  for (int m = 0; m < padded; ++m) {
    const double d = sx * g[0][m] + sy * g[1][m] + sz * g[2][m];
    min_dot = std::min(min_dot, d);
    min_cos2 = std::min(min_cos2, d * d / len2[m]);
  }
#endif
  s.axis[0] = static_cast<float>(sx), s.axis[1] = static_cast<float>(sy), s.axis[2] = static_cast<float>(sz);
  if (!(min_dot > 0.0)) {
    s.sin_half = 1.0f;  // α ≥ 90°: every plane through the origin meets the cone
  } else {
    // Widen slightly: float storage and the rounding of the test must not lose a direction.
    const double sin_half = std::sqrt(std::max(0.0, 1.0 - std::min(1.0, min_cos2)));
    s.sin_half = static_cast<float>(std::min(1.0, sin_half * (1.0 + 1e-6) + 1e-6));
  }
  return s;
}

template <int K>
Singleton bound_cell(const VolumeSpline& spline, int a, int b, int c) {
  double bez[K * K * K];
  spline.bezier_coefficients(a, b, c, bez);
  return bound_bezier<K>(bez);
}

// The singletons of z-slabs [z0, z1) into out (cell index order), as bound_cell gives them, bit for bit: the knot
// insertion along the first axis (VolumeSpline::bezier_coefficients' first stage, the same products and sums) is made
// once per control row and cell column and shared by the K × K cells that use the row, instead of once per cell.
template <int K>
void bound_slabs(const VolumeSpline& spline, int z0, int z1, Singleton* out) {
  const std::array<int, 3>& dims = spline.dims();
  const int cx = spline.span_count(0), cy = spline.span_count(1);
  bezier_cell::Matrix<K> m;
  for (int i = 0; i < K; ++i)
    for (int r = 0; r < K; ++r) m[i][r] = spline.to_bezier()[i * K + r];
  auto clamped = [&](int axis, int s, int r) { return std::clamp(spline.first_control(s) + r, 0, dims[axis] - 1); };
  const float* cp = spline.control_points().data();
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  // first[zp][(y · cx + a) · K + i]: coefficient i of cell column a along x, control row y of control plane zp.
  std::vector<std::vector<double>> first(dims[2]);
  auto plane = [&](int zp) -> const std::vector<double>& {
    std::vector<double>& f = first[zp];
    if (!f.empty()) return f;
    f.resize(static_cast<std::size_t>(dims[1]) * cx * K);
    for (int y = 0; y < dims[1]; ++y) {
      const float* row = cp + zp * nxy + static_cast<std::size_t>(y) * nx;
      for (int a = 0; a < cx; ++a) {
        double v[K];
        for (int r = 0; r < K; ++r) v[r] = row[clamped(0, a, r)];
        double* o = f.data() + (static_cast<std::size_t>(y) * cx + a) * K;
        for (int i = 0; i < K; ++i) {
          double sum = 0.0;
          for (int r = 0; r < K; ++r) sum += m[i][r] * v[r];
          o[i] = sum;
        }
      }
    }
    return f;
  };
  for (int c = z0; c < z1; ++c) {
    const std::vector<double>* planes[K];
    for (int k = 0; k < K; ++k) planes[k] = &plane(clamped(2, c, k));
    for (int zp = 0; zp < clamped(2, c, 0); ++zp) std::vector<double>().swap(first[zp]);  // no later slab needs it
    for (int b = 0; b < cy; ++b) {
      int rows[K];
      for (int j = 0; j < K; ++j) rows[j] = clamped(1, b, j);
      for (int a = 0; a < cx; ++a) {
        double tmp[K * K * K], in[K * K * K], bez[K * K * K];
        for (int k = 0; k < K; ++k)
          for (int j = 0; j < K; ++j) {
            const double* src = planes[k]->data() + (static_cast<std::size_t>(rows[j]) * cx + a) * K;
            for (int i = 0; i < K; ++i) tmp[i + K * (j + K * k)] = src[i];
          }
        bezier_cell::apply_axis<K, 1>(m, tmp, in);
        bezier_cell::apply_axis<K, 2>(m, in, bez);
        out[(static_cast<std::size_t>(c - z0) * cy + b) * cx + a] = bound_bezier<K>(bez);
      }
    }
  }
}

void bound_slabs(const VolumeSpline& spline, int z0, int z1, Singleton* out) {
  with_volume_order(spline.order(), [&](auto k) { bound_slabs<k>(spline, z0, z1, out); });
}

Singleton bound_cell(const VolumeSpline& spline, int a, int b, int c) {
  return with_volume_order(spline.order(), [&](auto k) { return bound_cell<k>(spline, a, b, c); });
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

// nearest_column for many directions: the axes as three padded float arrays, four dot products at a time. The same
// answer as nearest_column (the same float products and sums; the first of equal maxima).
class ColumnFinder {
 public:
  explicit ColumnFinder(const std::vector<glm::vec3>& axes) {
    const std::size_t padded = (axes.size() + 3) / 4 * 4;
    for (int c = 0; c < 3; ++c) {
      xyz_[c].resize(padded);
      // Padding repeats axis 0: a later equal maximum never wins.
      for (std::size_t i = 0; i < padded; ++i) xyz_[c][i] = axes[i < axes.size() ? i : 0][c];
    }
  }
  int operator()(const glm::vec3& d) const {
#if defined(__SSE2__)
    const __m128 dx = _mm_set1_ps(d.x), dy = _mm_set1_ps(d.y), dz = _mm_set1_ps(d.z);
    __m128 best = _mm_set1_ps(-2.0f);
    __m128i best_index = _mm_setzero_si128(), index = _mm_setr_epi32(0, 1, 2, 3);
    const __m128i four = _mm_set1_epi32(4);
    for (std::size_t i = 0; i < xyz_[0].size(); i += 4, index = _mm_add_epi32(index, four)) {
      const __m128 v =
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_loadu_ps(&xyz_[0][i]), dx), _mm_mul_ps(_mm_loadu_ps(&xyz_[1][i]), dy)),
                     _mm_mul_ps(_mm_loadu_ps(&xyz_[2][i]), dz));
      const __m128 greater = _mm_cmpgt_ps(v, best);
      best = _mm_or_ps(_mm_and_ps(greater, v), _mm_andnot_ps(greater, best));
      const __m128i g = _mm_castps_si128(greater);
      best_index = _mm_or_si128(_mm_and_si128(g, index), _mm_andnot_si128(g, best_index));
    }
    alignas(16) float lane[4];
    alignas(16) std::int32_t lane_index[4];
    _mm_store_ps(lane, best);
    _mm_store_si128(reinterpret_cast<__m128i*>(lane_index), best_index);
    int out = lane_index[0];
    float out_dot = lane[0];
    for (int k = 1; k < 4; ++k)
      if (lane[k] > out_dot || (lane[k] == out_dot && lane_index[k] < out)) out_dot = lane[k], out = lane_index[k];
    return out;
#else
    int best = 0;
    float best_dot = -2.0f;
    for (std::size_t i = 0; i < xyz_[0].size(); ++i) {
      const float v = xyz_[0][i] * d.x + xyz_[1][i] * d.y + xyz_[2][i] * d.z;
      if (v > best_dot) best_dot = v, best = static_cast<int>(i);
    }
    return best;
#endif
  }

 private:
  std::vector<float> xyz_[3];
};

// An unsigned integer whose ascending order is the descending order of the finite float v (−0 and +0 equal).
std::uint32_t descending_order_bits(float v) {
  if (v == 0.0f) v = 0.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  const std::uint32_t ascending = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return ~ascending;
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0));
}

}  // namespace

Singleton singleton_of_cell(const VolumeSpline& spline, int a, int b, int c) { return bound_cell(spline, a, b, c); }

SingletonTable build_singleton_table(const VolumeSpline& spline, const ProgressSink& progress, int rows, int columns) {
  if (rows < 1 || rows > kSingletonTableMaxRows || columns < 1 || columns > kSingletonTableMaxColumns)
    throw std::invalid_argument("singleton table needs 1…" + std::to_string(kSingletonTableMaxRows) + " rows and 1…" +
                                std::to_string(kSingletonTableMaxColumns) + " columns, got " + std::to_string(rows) +
                                " × " + std::to_string(columns));
  SingletonTable t;
  for (int a = 0; a < 3; ++a) t.cells_[a] = spline.span_count(a);
  const std::size_t slab = static_cast<std::size_t>(t.cells_[0]) * t.cells_[1];
  t.singletons_.resize(slab * t.cells_[2]);
  // Runs of slabs in parallel (each run shares its first-axis stage between neighbouring slabs), a few runs per
  // thread at a time so the progress moves.
  const int nz = t.cells_[2];
  const int run = std::max(1, std::min(8, nz / 64));
  const int batch = run * 2 * static_cast<int>(std::max<std::size_t>(1, tbb::this_task_arena::max_concurrency()));
  for (int z0 = 0; z0 < nz; z0 += batch) {
    progress.check(0.95 * double(z0) / nz);
    const int z1 = std::min(nz, z0 + batch);
    tbb::parallel_for(tbb::blocked_range<int>(z0, z1, run), [&](const tbb::blocked_range<int>& r) {
      bound_slabs(spline, r.begin(), r.end(), t.singletons_.data() + static_cast<std::size_t>(r.begin()) * slab);
    });
  }
  progress.check(0.95);
  t.rows_ = rows;
  t.set_columns(columns);
  t.file_bins();
  progress.check(1.0);
  return t;
}

void SingletonTable::set_columns(int columns) {
  column_axes_ = fibonacci_sphere(columns);
  // Column radius: the largest angle from a sphere point to its nearest axis, measured on a fine Fibonacci set and
  // widened by that set's own spacing (so it bounds every point of the sphere).
  const auto probe = fibonacci_sphere(kSingletonColumnProbes);
  double radius = 0.0;
  for (const glm::vec3& d : probe)
    radius = std::max(radius, angle_between(glm::dvec3(d), glm::dvec3(column_axes_[nearest_column(column_axes_, d)])));
  column_radius_ = radius + 2.0 * std::sqrt(4.0 * kPi / kSingletonColumnProbes);
}

void SingletonTable::file_bins() {
  range_min_ = INFINITY, range_max_ = -INFINITY;
  for (const Singleton& s : singletons_)
    range_min_ = std::min(range_min_, double(s.lo)), range_max_ = std::max(range_max_, double(s.hi));
  if (singletons_.empty()) range_min_ = range_max_ = 0.0;
  const int cols = columns();
  const std::size_t bins = static_cast<std::size_t>(rows_) * cols;
  const double span = range_max_ - range_min_;
  auto row_of = [&](double v) {
    if (!(span > 0.0)) return 0;
    return std::clamp(static_cast<int>(std::floor((v - range_min_) / span * rows_)), 0, rows_ - 1);
  };
  // Each non-constant singleton's bin (row of its lo, column nearest its cone axis), in parallel; per-thread counts and
  // widened cones, merged (sums and maxima: the same for any thread count).
  const std::size_t n = singletons_.size();
  std::vector<std::uint32_t> bin_of(n, UINT32_MAX);
  struct Partial {
    std::vector<std::uint32_t> counts;
    std::vector<float> half_angle;
  };
  const ColumnFinder find_column(column_axes_);
  tbb::enumerable_thread_specific<Partial> partials([bins] {
    return Partial{std::vector<std::uint32_t>(bins, 0), std::vector<float>(bins, 0.0f)};
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    Partial& p = partials.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Singleton& s = singletons_[i];
      if (!(s.hi > s.lo)) continue;  // constant: holds one level, and no silhouette (∇D = 0)
      const glm::vec3 axis(s.axis[0], s.axis[1], s.axis[2]);
      const bool full = half_angle(s) >= kPi;
      const int col = full ? 0 : find_column(axis);
      const std::uint32_t bin = static_cast<std::uint32_t>(row_of(s.lo) * cols + col);
      bin_of[i] = bin;
      ++p.counts[bin];
      const double widened =
          full ? kPi : angle_between(glm::dvec3(axis), glm::dvec3(column_axes_[col])) + half_angle(s) + 1e-6;
      p.half_angle[bin] = std::max(p.half_angle[bin], static_cast<float>(widened));
    }
  });
  std::vector<std::uint32_t> counts(bins, 0);
  bin_half_angle_.assign(bins, 0.0f);
  for (const Partial& p : partials)
    for (std::size_t b = 0; b < bins; ++b)
      counts[b] += p.counts[b], bin_half_angle_[b] = std::max(bin_half_angle_[b], p.half_angle[b]);
  bin_begin_.assign(bins + 1, 0);
  for (std::size_t b = 0; b < bins; ++b) bin_begin_[b + 1] = bin_begin_[b] + counts[b];
  bin_cells_.assign(bin_begin_[bins], 0);
  std::vector<std::uint32_t> fill(bin_begin_.begin(), bin_begin_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    if (bin_of[i] != UINT32_MAX) bin_cells_[fill[bin_of[i]]++] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t>().swap(bin_of);  // freed before the sort keys are made
  // Within a bin: hi descending, then cell ascending. The cells were filed in ascending order, so a stable sort by hi
  // alone gives that order: a least-significant-digit radix sort of hi's order bits (three passes of 11 bits, a pass
  // skipped when every key shares its digit), keys gathered once per bin so they stay in cache; small bins by
  // std::sort of 64-bit (hi bits, cell) keys. 12 bytes per cell of the bins being sorted at once.
  tbb::parallel_for(std::size_t(0), bins, [&](std::size_t b) {
    const std::uint32_t first = bin_begin_[b], count = bin_begin_[b + 1] - first;
    if (count < 2) return;
    std::uint32_t* cells = bin_cells_.data() + first;
    if (count < 256) {
      std::vector<std::uint64_t> keys(count);
      for (std::uint32_t j = 0; j < count; ++j)
        keys[j] = (static_cast<std::uint64_t>(descending_order_bits(singletons_[cells[j]].hi)) << 32) | cells[j];
      std::sort(keys.begin(), keys.end());
      for (std::uint32_t j = 0; j < count; ++j) cells[j] = static_cast<std::uint32_t>(keys[j]);
      return;
    }
    std::vector<std::uint32_t> key(count), key_out(count), cell_out(count);
    for (std::uint32_t j = 0; j < count; ++j) key[j] = descending_order_bits(singletons_[cells[j]].hi);
    std::uint32_t *key_in = key.data(), *cell_in = cells, *key_to = key_out.data(), *cell_to = cell_out.data();
    constexpr int kDigitBits = 11, kBuckets = 1 << kDigitBits;
    for (int shift = 0; shift < 32; shift += kDigitBits) {
      std::uint32_t offset[kBuckets] = {};
      for (std::uint32_t j = 0; j < count; ++j) ++offset[(key_in[j] >> shift) & (kBuckets - 1)];
      if (offset[(key_in[0] >> shift) & (kBuckets - 1)] == count) continue;  // one digit for all: order unchanged
      std::uint32_t sum = 0;
      for (std::uint32_t& o : offset) sum += std::exchange(o, sum);
      for (std::uint32_t j = 0; j < count; ++j) {
        const std::uint32_t at = offset[(key_in[j] >> shift) & (kBuckets - 1)]++;
        key_to[at] = key_in[j], cell_to[at] = cell_in[j];
      }
      std::swap(key_in, key_to);
      std::swap(cell_in, cell_to);
    }
    if (cell_in != cells) std::copy(cell_in, cell_in + count, cells);
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
      const auto end =
          std::partition_point(first, last, [&](std::uint32_t cell) { return double(singletons[cell].hi) >= iso; });
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
  return query(singletons_, bin_begin_, bin_cells_, rows_, columns(), range_min_, range_max_, iso, CellOrder::ascending,
               [](std::size_t, int) { return true; });
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

}  // namespace trispline::core
