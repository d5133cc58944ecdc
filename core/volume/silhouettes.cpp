#include "core/volume/silhouettes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <optional>
#include <unordered_map>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/volume/bezier_cell.h"

namespace trispline::core {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Curve tracing: steps of at most kStepMax index units, halved down to kStepMin where the corrector fails or the
// tangent turns by more than kMaxTurnDeg in one step.
constexpr double kStepMax = 0.5, kStepMin = 1.0 / 128.0, kMaxTurnDeg = 25.0;
// A march stops where it comes within kJoinRadius index units of a point already traced (a point on a chord of length
// kStepMax is within kStepMax/2 of one of its ends).
constexpr double kJoinRadius = 0.75 * kStepMax;
constexpr int kCorrectorIterations = 8, kSeedIterations = 6, kMaxSteps = 1 << 16;
// Cells per block axis: blocks are traced independently (in parallel) and their traces joined at the block faces.
constexpr int kBlock = 16;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The view in index space: the silhouette condition G·V = 0 in world coordinates is g·w = 0 with g the index-space
// gradient and w = A⁻¹V (orthographic) or x − eye_index (perspective), A the linear part of index_to_world.
struct IndexView {
  bool perspective = true;
  glm::dvec3 eye{0.0};  // index space
  glm::dvec3 v{0.0};    // index space, unit (orthographic)
  glm::dvec3 w(const glm::dvec3& x) const { return perspective ? x - eye : v; }
};

IndexView index_view(const VolumeSpline& spline, const SilhouetteView& view) {
  IndexView iv;
  iv.perspective = view.perspective;
  if (view.perspective) {
    iv.eye = glm::dvec3(spline.world_to_index() * glm::dvec4(view.eye, 1.0));
  } else {
    iv.v = glm::dmat3(spline.world_to_index()) * view.direction;
    iv.v /= glm::length(iv.v);
  }
  return iv;
}

// What every solve needs: the spline, the level, the view and the stopping accuracy.
struct Problem {
  const VolumeSpline& spline;
  const SingletonTable& table;
  IndexView view;
  double iso = 0.0;
  double range = 1.0;  // range(D) for the relative value residual
  double accuracy = 1e-7;
  glm::dmat3 to_world{1.0};  // linear part of index_to_world
};

struct CurvePoint {
  glm::dvec3 x;           // index space
  glm::dvec3 tangent;     // index space, unit: ∇D × ∇(g·w), the curve's direction
  float gradient_norm;    // |∇D| per millimetre
  double value_residual;  // |D − c| / range
  double dot_residual;    // |Ĝ·V̂| in world space
  int iterations;         // Newton iterations it took
};

// Newton–Raphson on F(x) = (D(x) − c, ∇D(x)·w(x)) = 0 (seed Eq. 7.2) from x. With plane_axis < 0 the steps are the
// minimum-norm solutions −Jᵀ(JJᵀ)⁻¹F (2 equations, 3 unknowns); with plane_axis = a, x[a] stays fixed and the step
// solves the 2 × 2 system in the other two coordinates (the curve's crossing of the plane x[a] = const). Returns false
// when it does not converge within `iterations`, stops contracting, leaves lo…hi, ends at a singular point
// (∇D ∥ ∇(g·w): no tangent), or when abort(x) says so after a step.
struct NoAbort {
  bool operator()(const glm::dvec3&) const { return false; }
};

template <class Abort = NoAbort>
bool solve_point(const Problem& pb, glm::dvec3 x, const glm::dvec3& lo, const glm::dvec3& hi, int iterations,
                 CurvePoint& out, int plane_axis = -1, Abort&& abort = {}) {
  const IndexView& view = pb.view;
  double last_step = INFINITY;
  for (int it = 0; it <= iterations; ++it) {
    const VolumeJet j = pb.spline.jet(x);
    const glm::dvec3 w = view.w(x);
    const double f1 = j.value - pb.iso, f2 = glm::dot(j.gradient, w);
    const glm::dvec3 gw = pb.spline.world_gradient(j.gradient);
    const glm::dvec3 ww = pb.to_world * w;
    const double gl = glm::length(gw), wl = glm::length(ww);
    if (!(gl > 0.0) || !(wl > 0.0)) return false;
    const glm::dvec3 r1 = j.gradient;
    const glm::dvec3 r2 = j.hessian * w + (view.perspective ? j.gradient : glm::dvec3(0.0));
    const double value_res = std::abs(f1) / pb.range, dot_res = std::abs(glm::dot(gw, ww)) / (gl * wl);
    if (value_res <= pb.accuracy && dot_res <= pb.accuracy) {
      const glm::dvec3 t = glm::cross(r1, r2);
      const double tl = glm::length(t);
      if (!(tl > 0.0) || !std::isfinite(tl)) return false;
      out.x = x;
      out.tangent = t / tl;
      out.value_residual = value_res;
      out.dot_residual = dot_res;
      out.gradient_norm = static_cast<float>(gl);
      out.iterations = it;
      return true;
    }
    if (it == iterations) break;
    glm::dvec3 step(0.0);
    if (plane_axis < 0) {
      const double a = glm::dot(r1, r1), b = glm::dot(r1, r2), c = glm::dot(r2, r2);
      const double det = a * c - b * b;
      if (!(det > 1e-300) || !(std::abs(det) > 1e-14 * a * c)) return false;
      const double l1 = (c * f1 - b * f2) / det, l2 = (a * f2 - b * f1) / det;
      step = -(l1 * r1 + l2 * r2);
    } else {
      const int u = (plane_axis + 1) % 3, v = (plane_axis + 2) % 3;
      const double det = r1[u] * r2[v] - r1[v] * r2[u];
      const double scale = glm::length(r1) * glm::length(r2);
      if (!(std::abs(det) > 1e-10 * scale)) return false;
      step[u] = -(f1 * r2[v] - f2 * r1[v]) / det;
      step[v] = -(r1[u] * f2 - r2[u] * f1) / det;
    }
    const double sl = glm::length(step);
    if (!std::isfinite(sl)) return false;
    // Past the first two steps Newton converging to a regular point at least halves its step each time; otherwise
    // it is wandering.
    if (it >= 2 && sl > 0.5 * last_step) return false;
    // The full step points (to first order) at the solution: well outside lo…hi, it would not be accepted.
    const glm::dvec3 target = x + step;
    if (glm::any(glm::lessThan(target, lo - 0.25)) || glm::any(glm::greaterThan(target, hi + 0.25))) return false;
    last_step = sl;
    if (sl > 0.5) step *= 0.5 / sl;
    x += step;
    if (glm::any(glm::lessThan(x, lo)) || glm::any(glm::greaterThan(x, hi)) || abort(x)) return false;
  }
  return false;
}

// Whether some direction in the cone (axis a, sine s_a) is orthogonal to some direction in the cone (unit axis w,
// half-angle with sine s_w, cosine c_w): |angle(a, w) − 90°| ≤ α + γ.
bool cones_admit_orthogonal(const Singleton& s, const glm::dvec3& w, double s_w, double c_w) {
  const double sa = s.sin_half;
  if (sa >= 1.0) return true;
  const double ca = std::sqrt(std::max(0.0, 1.0 - sa * sa));
  const double sin_sum = sa * c_w + ca * s_w;  // sin(α + γ)
  if (ca * c_w - sa * s_w <= 0.0) return true;  // α + γ ≥ 90°
  const double d = std::abs(double(s.axis[0]) * w.x + double(s.axis[1]) * w.y + double(s.axis[2]) * w.z);
  return d <= sin_sum;
}

// Range of G·w over a (sub-)cell from its Bézier coefficients: the hull of the gradient's vector coefficients dotted
// with w (orthographic), or with w at the centre plus the largest change of w over the box (perspective:
// g·(x − eye) = g·(centre − eye) + g·(x − centre), |x − centre| ≤ (√3/2)·h). `h`: the box's side in index units (the
// coefficients' local unit). Returns false when 0 is outside the range.
template <int K>
bool dot_range_holds_zero(const double* coefs, const glm::dvec3& centre, const IndexView& view) {
  constexpr int n = K * K * K;
  double g[3][64];
  bezier_cell::gradient_vectors<K>(coefs, g);
  const glm::dvec3 w = view.w(centre);
  double fmin = INFINITY, fmax = -INFINITY, g2max = 0.0;
  for (int m = 0; m < n; ++m) {
    const double f = g[0][m] * w.x + g[1][m] * w.y + g[2][m] * w.z;
    fmin = std::min(fmin, f), fmax = std::max(fmax, f);
    g2max = std::max(g2max, g[0][m] * g[0][m] + g[1][m] * g[1][m] + g[2][m] * g[2][m]);
  }
  if (view.perspective) {
    // Coefficients are per local unit (h index units): |g per index unit| = |g|/h, times (√3/2)·h.
    const double slack = std::sqrt(g2max) * std::sqrt(3.0) * 0.5;
    fmin -= slack, fmax += slack;
  }
  return fmin <= 0.0 && 0.0 <= fmax;
}

#if defined(__SSE2__)
// A quick, conservative form of the whole-cell G·w hull test for cubic cells (order 4), in single precision with SSE:
// the Bézier coefficients (the knot-insertion matrix along each axis), the gradient's raised vector coefficients and
// their dot products with w, four coefficients (one x-row) at a time. Float rounding is covered by a margin of
// 1e-4·max|P|·|w|₁ (P the control points), ten times the rounding these few dozen operations can make on the
// raised derivative coefficients (≲ 12 ulp of max|P| per coefficient, times 6 for the differences), so a cell it rejects would be rejected in
// double precision too; a cell it passes goes on to the exact tests.
class CubicHullTest {
 public:
  CubicHullTest(const VolumeSpline& spline, const IndexView& view)
      : spline_(spline), view_(view), max_abs_(std::max(std::abs(spline.control_min()), std::abs(spline.control_max()))) {
    const auto& m = spline.to_bezier();
    for (int a = 0; a < 4; ++a)
      for (int r = 0; r < 4; ++r) m_[a][r] = static_cast<float>(m[a * 4 + r]);
    for (int r = 0; r < 4; ++r) column_[r] = _mm_setr_ps(m_[0][r], m_[1][r], m_[2][r], m_[3][r]);
  }

  // False when G·w cannot vanish on cell (a, b, c).
  bool may_hold_zero(int a, int b, int c) const {
    const auto& dims = spline_.dims();
    const std::size_t nx = dims[0], nxy = nx * dims[1];
    const float* cp = spline_.control_points().data();
    int ix[4], iy[4], iz[4];
    for (int r = 0; r < 4; ++r) {
      ix[r] = std::clamp(spline_.first_control(a) + r, 0, dims[0] - 1);
      iy[r] = std::clamp(spline_.first_control(b) + r, 0, dims[1] - 1);
      iz[r] = std::clamp(spline_.first_control(c) + r, 0, dims[2] - 1);
    }
    const bool contiguous = ix[3] - ix[0] == 3;
    // p[z][y] = one x-row of control points, then rows of Bézier coefficients (knot insertion along z, y, then x).
    __m128 p[4][4], q[4][4];
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y) {
        const float* row = cp + iz[z] * nxy + iy[y] * nx;
        p[z][y] = contiguous ? _mm_loadu_ps(row + ix[0]) : _mm_setr_ps(row[ix[0]], row[ix[1]], row[ix[2]], row[ix[3]]);
      }
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y) q[z][y] = combine(m_[z], p[0][y], p[1][y], p[2][y], p[3][y]);
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y) p[z][y] = combine(m_[y], q[z][0], q[z][1], q[z][2], q[z][3]);
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y) p[z][y] = along_x(p[z][y]);
    // Raised derivative vectors e_k = k·Δ_{k−1} + (3 − k)·Δ_k along each axis, dotted with w.
    const glm::dvec3 wc = view_.w(glm::dvec3(spline_.span_begin(a), spline_.span_begin(b), spline_.span_begin(c)) + 0.5);
    const __m128 wx = _mm_set1_ps(static_cast<float>(wc.x)), wy = _mm_set1_ps(static_cast<float>(wc.y)),
                 wz = _mm_set1_ps(static_cast<float>(wc.z));
    const __m128 up = _mm_setr_ps(0.f, 1.f, 2.f, 3.f), down = _mm_setr_ps(3.f, 2.f, 1.f, 0.f);
    __m128 fmin = _mm_set1_ps(INFINITY), fmax = _mm_set1_ps(-INFINITY), g2 = _mm_setzero_ps();
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y) {
        const __m128 v = p[z][y];
        // x: differences inside the row.
        const __m128 next = _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 2, 1));  // b1 b2 b3 b3
        const __m128 prev = _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 1, 0, 0));  // b0 b0 b1 b2
        const __m128 ex = _mm_add_ps(_mm_mul_ps(up, _mm_sub_ps(v, prev)), _mm_mul_ps(down, _mm_sub_ps(next, v)));
        const __m128 ey = raised(p[z], y);
        const __m128 ez = raised_z(p, z, y);
        const __m128 tx = _mm_mul_ps(wx, ex), ty = _mm_mul_ps(wy, ey), tz = _mm_mul_ps(wz, ez);
        const __m128 f = _mm_add_ps(_mm_add_ps(tx, ty), tz);
        fmin = _mm_min_ps(fmin, f), fmax = _mm_max_ps(fmax, f);
        g2 = _mm_max_ps(g2, _mm_add_ps(_mm_add_ps(_mm_mul_ps(ex, ex), _mm_mul_ps(ey, ey)), _mm_mul_ps(ez, ez)));
      }
    const double lo = hmin(fmin), hi = hmax(fmax);
    double slack = 1e-4 * max_abs_ * (std::abs(wc.x) + std::abs(wc.y) + std::abs(wc.z)) + 1e-30;
    if (view_.perspective) slack += std::sqrt(hmax(g2)) * (1.0 + 1e-4) * std::sqrt(3.0) * 0.5;
    return lo - slack <= 0.0 && 0.0 <= hi + slack;
  }

 private:
  static __m128 combine(const float* m, __m128 r0, __m128 r1, __m128 r2, __m128 r3) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[0]), r0), _mm_mul_ps(_mm_set1_ps(m[1]), r1)),
                      _mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[2]), r2), _mm_mul_ps(_mm_set1_ps(m[3]), r3)));
  }
  // The knot-insertion matrix applied inside one x-row: out[a] = Σ_r m[a][r]·v[r].
  __m128 along_x(__m128 v) const {
    return _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0)), column_[0]),
                   _mm_mul_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 1, 1)), column_[1])),
        _mm_add_ps(_mm_mul_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 2, 2, 2)), column_[2]),
                   _mm_mul_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 3, 3)), column_[3])));
  }
  // e_k along y (rows[k]) and z (p[k][y]) with k the row's index: k·(r_k − r_{k−1}) + (3 − k)·(r_{k+1} − r_k).
  static __m128 raised(const __m128* rows, int k) {
    __m128 e = _mm_setzero_ps();
    if (k > 0) e = _mm_mul_ps(_mm_set1_ps(float(k)), _mm_sub_ps(rows[k], rows[k - 1]));
    if (k < 3) e = _mm_add_ps(e, _mm_mul_ps(_mm_set1_ps(float(3 - k)), _mm_sub_ps(rows[k + 1], rows[k])));
    return e;
  }
  static __m128 raised_z(const __m128 (*p)[4], int k, int y) {
    __m128 e = _mm_setzero_ps();
    if (k > 0) e = _mm_mul_ps(_mm_set1_ps(float(k)), _mm_sub_ps(p[k][y], p[k - 1][y]));
    if (k < 3) e = _mm_add_ps(e, _mm_mul_ps(_mm_set1_ps(float(3 - k)), _mm_sub_ps(p[k + 1][y], p[k][y])));
    return e;
  }
  static double hmin(__m128 v) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return std::min(std::min(f[0], f[1]), std::min(f[2], f[3]));
  }
  static double hmax(__m128 v) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return std::max(std::max(f[0], f[1]), std::max(f[2], f[3]));
  }

  const VolumeSpline& spline_;
  const IndexView& view_;
  double max_abs_;  // max |control point|
  float m_[4][4];
  __m128 column_[4];
};
#endif

// The de Casteljau matrices restricting [0,1] to its s equal parts (s = 1…4), made once per order and s.
template <int K>
const std::array<bezier_cell::Matrix<K>, 4>& restrictions(int s) {
  static const auto table = [] {
    std::array<std::array<bezier_cell::Matrix<K>, 4>, 5> t{};
    for (int n = 1; n <= 4; ++n)
      for (int i = 0; i < n; ++i) t[n][i] = bezier_cell::restriction<K>(double(i) / n, double(i + 1) / n);
    return t;
  }();
  return table[s];
}

// The seeds of one candidate singleton (seed §7.3.3): it is split into `subdivision`³ sub-cells (de Casteljau on its
// Bézier form); each sub-cell whose value range holds c and whose range of G·w holds 0 yields its centre. Slabs go
// first (z, then y within a surviving slab, then x): a slab whose value range misses c is not split further. `seed`
// is called with each centre (index space) and returns true to stop.
template <int K, class Seed>
void seed_cell(const Problem& pb, int a, int b, int c, int subdivision, bool whole_cell_tested, Seed&& seed) {
  constexpr int n = K * K * K;
  const VolumeSpline& spline = pb.spline;
  const glm::dvec3 origin(spline.span_begin(a), spline.span_begin(b), spline.span_begin(c));
  // One seed per singleton whose hull test is done: its centre (the singleton's range holds c, it is a candidate).
  if (subdivision == 1 && whole_cell_tested) {
    seed(origin + 0.5);
    return;
  }
  double bez[n];
  spline.bezier_coefficients(a, b, c, bez);
  // The whole singleton first: its G·w hull must hold 0 before any sub-cell is made.
  if (!whole_cell_tested && !dot_range_holds_zero<K>(bez, origin + 0.5, pb.view)) return;
  const int s = subdivision;
  const double h = 1.0 / s;
  const auto& restrict = restrictions<K>(s);
  const double iso = pb.iso;
  auto holds_iso = [iso](const double* q) {
    double mn = q[0], mx = q[0];
    for (int m = 1; m < n; ++m) mn = std::min(mn, q[m]), mx = std::max(mx, q[m]);
    return mn <= iso && iso <= mx;
  };
  double zslab[n], yrow[n], sub[n];
  for (int sz = 0; sz < s; ++sz) {
    if (s > 1) bezier_cell::apply<K>(restrict[sz], bez, zslab, 2);
    else std::copy(bez, bez + n, zslab);
    if (s > 1 && !holds_iso(zslab)) continue;
    for (int sy = 0; sy < s; ++sy) {
      if (s > 1) bezier_cell::apply<K>(restrict[sy], zslab, yrow, 1);
      else std::copy(zslab, zslab + n, yrow);
      if (s > 1 && !holds_iso(yrow)) continue;
      for (int sx = 0; sx < s; ++sx) {
        if (s > 1) bezier_cell::apply<K>(restrict[sx], yrow, sub, 0);
        else std::copy(yrow, yrow + n, sub);
        if (!holds_iso(sub)) continue;
        const glm::dvec3 centre = origin + glm::dvec3(sx + 0.5, sy + 0.5, sz + 0.5) * h;
        if (s > 1 && !dot_range_holds_zero<K>(sub, centre, pb.view)) continue;
        if (seed(centre)) return;
      }
    }
  }
}

template <class Seed>
void seed_cell(const Problem& pb, int a, int b, int c, int subdivision, bool whole_cell_tested, Seed&& seed) {
  switch (pb.spline.order()) {
    case 2: return seed_cell<2>(pb, a, b, c, subdivision, whole_cell_tested, seed);
    case 3: return seed_cell<3>(pb, a, b, c, subdivision, whole_cell_tested, seed);
    default: return seed_cell<4>(pb, a, b, c, subdivision, whole_cell_tested, seed);
  }
}

// One piece of curve traced inside one block. Its ends are either free (the curve ended, or tracing failed) or lie on
// a face of the block, found exactly (solve_point on the face plane) so that the neighbour block's trace of the same
// curve ends at the same point.
struct Trace {
  std::vector<CurvePoint> points;
  bool closed = false;
  bool on_face[2] = {false, false};  // first, last point
};

// Per-thread memory of a block: which cells a trace has crossed, and the traced points filed by cell.
struct BlockScratch {
  struct Entry {
    glm::dvec3 x;
    std::int32_t trace, next;
    std::int32_t order;  // the point's number in its trace (in the order traced)
  };
  std::vector<std::int32_t> head;       // per local cell: first Entry of the cell, −1 none
  std::vector<unsigned char> visited;   // per local cell: a trace crossed it
  std::vector<std::uint32_t> touched;   // local cells to reset
  std::vector<Entry> entries;
  void reset() {
    for (std::uint32_t c : touched) head[c] = -1, visited[c] = 0;
    touched.clear();
    entries.clear();
  }
};

// Traces the silhouette curves of one block of cells (predictor–corrector continuation from each seed, both ways,
// until the curve closes, leaves the block, runs into another trace or cannot be followed).
class BlockTracer {
 public:
  BlockTracer(const Problem& pb, const glm::ivec3& first, const glm::ivec3& last, BlockScratch& scratch)
      : pb_(pb), first_(first), last_(last), s_(scratch) {
    const auto& dims = pb.spline.dims();
    for (int a = 0; a < 3; ++a) {
      extent_[a] = last[a] - first[a];
      lo_[a] = std::max(pb.spline.span_begin(first[a]), 0.0);
      hi_[a] = std::min(pb.spline.span_begin(last[a]), double(dims[a] - 1));
    }
    const std::size_t cells = static_cast<std::size_t>(kBlock) * kBlock * kBlock;
    if (s_.head.size() != cells) s_.head.assign(cells, -1), s_.visited.assign(cells, 0);
    s_.reset();
  }
  ~BlockTracer() { s_.reset(); }

  std::vector<Trace> traces;

  bool visited(const glm::ivec3& cell) const { return s_.visited[local(cell)] != 0; }

  // A traced point within r (≤ 1) index units of x — of another trace than `own`, or of trace `own` numbered below
  // `own_before` — or null.
  const BlockScratch::Entry* near_trace(const glm::dvec3& x, double r, std::int32_t own = -1,
                                        std::int32_t own_before = 0) const {
    const glm::ivec3 c = cell_of(x);
    const glm::ivec3 lo = glm::max(c - 1, first_) - first_, hi = glm::min(c + 1, last_ - 1) - first_;
    const double r2 = r * r;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y) {
        const std::size_t row = kBlock * (static_cast<std::size_t>(y) + kBlock * static_cast<std::size_t>(z));
        for (int xi = lo.x; xi <= hi.x; ++xi)
          for (std::int32_t e = s_.head[row + xi]; e >= 0; e = s_.entries[e].next) {
            const BlockScratch::Entry& en = s_.entries[e];
            const glm::dvec3 d = en.x - x;
            if ((en.trace != own || en.order < own_before) && glm::dot(d, d) < r2) return &en;
          }
      }
    return nullptr;
  }

  bool inside(const glm::dvec3& x) const {
    return !glm::any(glm::lessThan(x, lo_)) && !glm::any(glm::greaterThan(x, hi_));
  }

  glm::ivec3 cell_of(const glm::dvec3& x) const {
    glm::ivec3 c;
    const double shift = pb_.spline.span_begin(0);
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor(x[a] - shift)), first_[a], last_[a] - 1);
    return c;
  }

  // Traces the curve through p both ways and keeps it when it is more than a point.
  void trace_from(const CurvePoint& p) {
    const auto id = static_cast<std::int32_t>(traces.size());
    next_order_ = 0;
    add_point(p.x, id);
    std::vector<CurvePoint> ahead, behind;
    const End e1 = march(p, 1.0, id, &p.x, ahead);
    Trace tr;
    if (e1 == End::closed) {
      tr.closed = true;
      tr.points.reserve(ahead.size() + 1);
      tr.points.push_back(p);
      tr.points.insert(tr.points.end(), ahead.begin(), ahead.end());
    } else {
      // Backwards, a loop the forward march could not close ends where the forward march stopped.
      const End e0 = march(p, -1.0, id, ahead.empty() ? nullptr : &ahead.back().x, behind);
      tr.points.reserve(behind.size() + ahead.size() + 1);
      tr.points.insert(tr.points.end(), behind.rbegin(), behind.rend());
      tr.points.push_back(p);
      tr.points.insert(tr.points.end(), ahead.begin(), ahead.end());
      tr.closed = e0 == End::closed;
      tr.on_face[0] = e0 == End::face;
      tr.on_face[1] = e1 == End::face;
    }
    if (tr.points.size() >= 2) traces.push_back(std::move(tr));
  }

 private:
  enum class End { failed, face, closed, joined };

  std::size_t local(const glm::ivec3& c) const {
    return static_cast<std::size_t>(c.x - first_.x) +
           kBlock * (static_cast<std::size_t>(c.y - first_.y) + kBlock * static_cast<std::size_t>(c.z - first_.z));
  }

  void visit(const glm::ivec3& c) {
    const std::size_t l = local(c);
    if (!s_.visited[l] && s_.head[l] < 0) s_.touched.push_back(static_cast<std::uint32_t>(l));
    s_.visited[l] = 1;
  }

  void add_point(const glm::dvec3& x, std::int32_t trace) {
    const std::int32_t order = next_order_++;
    const glm::ivec3 c = cell_of(x);
    const std::size_t l = local(c);
    if (!s_.visited[l] && s_.head[l] < 0) s_.touched.push_back(static_cast<std::uint32_t>(l));
    s_.visited[l] = 1;
    s_.entries.push_back({x, trace, s_.head[l], order});
    s_.head[l] = static_cast<std::int32_t>(s_.entries.size() - 1);
  }

  // Marks the cells the segment a→b crosses (samples every ¼ index unit).
  void visit_segment(const glm::dvec3& a, const glm::dvec3& b) {
    const int n = 1 + static_cast<int>(glm::length(b - a) * 4.0);
    for (int i = 0; i <= n; ++i) visit(cell_of(a + (b - a) * (double(i) / n)));
  }

  // Follows the curve from `start` along sign·tangent, appending the points after it to `out`; the march closes when it
  // comes back to *close_to (may be null) after going some way.
  End march(const CurvePoint& start, double sign, std::int32_t id, const glm::dvec3* close_to,
            std::vector<CurvePoint>& out) {
    const double min_turn_cos = std::cos(kMaxTurnDeg * kPi / 180.0);
    const glm::dvec3 margin(1.0);
    glm::dvec3 x = start.x, t = sign * start.tangent;
    glm::dvec3 bend(0.0);  // dt/ds from the last step: the predictor follows the curve's bending
    double h = kStepMax, travelled = 0.0;
    int easy = 0;
    // A curve in one block is far shorter than kMaxSteps steps; the bound only stops a runaway march.
    for (int n = 0; n < kMaxSteps; ++n) {
      CurvePoint q;
      const glm::dvec3 predicted = x + h * t + (0.5 * h * h) * bend;
      bool ok = solve_point(pb_, predicted, lo_ - margin, hi_ + margin, kCorrectorIterations, q);
      double dl = 0.0;
      if (ok) {
        const glm::dvec3 d = q.x - x;
        dl = glm::length(d);
        // A step goes forward by about h, lands near the predictor (not on a neighbouring branch) and turns little.
        ok = dl >= 0.25 * h && dl <= 2.0 * h && glm::dot(d, t) >= 0.5 * dl &&
             glm::length(q.x - predicted) <= 0.35 * h && std::abs(glm::dot(q.tangent, t)) >= min_turn_cos;
      }
      if (!ok) {
        h *= 0.5, easy = 0;
        if (h < kStepMin) return End::failed;
        continue;
      }
      if (glm::dot(q.tangent, t) < 0.0) q.tangent = -q.tangent;
      if (!inside(q.x)) {
        // Leaving the block: the crossing of the face the segment x→q leaves through, solved on the face plane.
        double s = 1.0;
        int axis = -1;
        double plane = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double bound = q.x[a] > hi_[a] ? hi_[a] : (q.x[a] < lo_[a] ? lo_[a] : NAN);
          if (std::isnan(bound)) continue;
          const double sa = (bound - x[a]) / (q.x[a] - x[a]);
          if (sa < s) s = sa, axis = a, plane = bound;
        }
        if (axis < 0) return End::failed;
        glm::dvec3 y = x + s * (q.x - x);
        y[axis] = plane;
        CurvePoint f;
        const glm::dvec3 tol(1e-9);
        if (!solve_point(pb_, y, lo_ - margin, hi_ + margin, kCorrectorIterations, f, axis) ||
            glm::length(f.x - y) > h || glm::any(glm::lessThan(f.x, lo_ - tol)) ||
            glm::any(glm::greaterThan(f.x, hi_ + tol)))
          return End::failed;
        if (glm::dot(f.tangent, t) < 0.0) f.tangent = -f.tangent;
        visit_segment(x, f.x);
        out.push_back(f);
        return End::face;
      }
      // Another trace, or this one (not its last few points): the curve is known from here on. Back at close_to, the
      // curve is a closed loop.
      if (const BlockScratch::Entry* en = near_trace(q.x, kJoinRadius, id, next_order_ - 8)) {
        if (close_to && en->trace == id && en->x == *close_to) {
          visit_segment(x, *close_to);
          return End::closed;
        }
        return End::joined;
      }
      visit_segment(x, q.x);
      add_point(q.x, id);
      out.push_back(q);
      travelled += dl;
      bend = (q.tangent - t) / dl;
      x = q.x, t = q.tangent;
      if (q.iterations <= 3 && ++easy >= 2) h = std::min(kStepMax, 1.5 * h);
    }
    return End::failed;
  }

  const Problem& pb_;
  glm::ivec3 first_, last_;  // cells first…last − 1 per axis
  glm::ivec3 extent_{0};
  glm::dvec3 lo_{0.0}, hi_{0.0};  // the block's box in index space, clipped to the domain
  std::int32_t next_order_ = 0;   // number of the next point of the trace being traced
  BlockScratch& s_;
};

// Joins the traces of all blocks at their shared face points into polylines (index lists of traces with direction),
// in the traces' order: open chains first (from a free end), then cycles.
struct ChainPiece {
  std::uint32_t trace;
  bool reversed;
};
struct Chain {
  std::vector<ChainPiece> pieces;
  bool closed = false;
};

std::vector<Chain> join_traces(const std::vector<Trace>& traces) {
  const std::size_t n = traces.size();
  // Face ends filed in a hash grid of 1/256 index units; two ends match within 1e-3 index units. Both solve the same
  // three equations, but the stopping test is on the residuals, so where the curve meets the face at a shallow angle
  // the two solutions can differ by ~1e-5; distinct curves are never that close on a face at these residuals.
  constexpr double kCell = 1.0 / 256.0, kMatch = 1e-3;
  auto key_of = [](const glm::i64vec3& q) {
    return static_cast<std::uint64_t>(q.x) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(q.y) * 0xC2B2AE3D27D4EB4Full ^
           static_cast<std::uint64_t>(q.z) * 0x165667B19E3779F9ull;
  };
  auto quantise = [](const glm::dvec3& x) {
    return glm::i64vec3(std::floor(x.x / kCell), std::floor(x.y / kCell), std::floor(x.z / kCell));
  };
  auto end_point = [&](std::size_t e) -> const glm::dvec3& {
    const Trace& t = traces[e / 2];
    return e % 2 == 0 ? t.points.front().x : t.points.back().x;
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t e = 0; e < 2 * n; ++e)
    if (traces[e / 2].on_face[e % 2]) grid[key_of(quantise(end_point(e)))].push_back(static_cast<std::uint32_t>(e));
  std::vector<std::int64_t> partner(2 * n, -1);
  for (std::size_t e = 0; e < 2 * n; ++e) {
    if (!traces[e / 2].on_face[e % 2] || partner[e] >= 0) continue;
    const glm::dvec3& p = end_point(e);
    const glm::i64vec3 q = quantise(p);
    std::int64_t best = -1;
    double best_d = kMatch;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = grid.find(key_of(q + glm::i64vec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (std::uint32_t f : it->second) {
            if (f == e || partner[f] >= 0) continue;
            const double d = glm::length(end_point(f) - p);
            if (d < best_d || (d == best_d && static_cast<std::int64_t>(f) < best)) best_d = d, best = f;
          }
        }
    if (best >= 0) partner[e] = best, partner[best] = static_cast<std::int64_t>(e);
  }
  std::vector<char> used(n, 0);
  std::vector<Chain> chains;
  auto walk = [&](std::size_t start, int entry) {
    Chain chain;
    std::size_t cur = start;
    while (!used[cur]) {
      used[cur] = 1;
      chain.pieces.push_back({static_cast<std::uint32_t>(cur), entry == 1});
      const std::int64_t next = partner[2 * cur + (1 - entry)];
      if (next < 0) break;
      if (static_cast<std::size_t>(next / 2) == start && used[start]) {
        chain.closed = true;
        break;
      }
      cur = static_cast<std::size_t>(next / 2), entry = static_cast<int>(next % 2);
    }
    return chain;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (used[i]) continue;
    if (traces[i].closed) {
      used[i] = 1;
      chains.push_back({{{static_cast<std::uint32_t>(i), false}}, true});
    } else if (partner[2 * i] < 0) {
      chains.push_back(walk(i, 0));
    } else if (partner[2 * i + 1] < 0) {
      chains.push_back(walk(i, 1));
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!used[i]) chains.push_back(walk(i, 0));
  return chains;
}

void check_params(double iso, const SilhouetteView& view, const SilhouetteParams& params) {
  if (!std::isfinite(iso)) throw std::invalid_argument("the iso-level must be a finite number");
  if (params.subdivision < 1 || params.subdivision > 4)
    throw std::invalid_argument("subdivision must be 1…4 sub-cells per singleton axis, got " +
                                std::to_string(params.subdivision));
  if (!(params.accuracy >= 1e-12 && params.accuracy <= 1e-2))
    throw std::invalid_argument("accuracy must be in [1e-12, 1e-2], got " + std::to_string(params.accuracy));
  if (view.perspective) {
    if (!std::isfinite(view.eye.x) || !std::isfinite(view.eye.y) || !std::isfinite(view.eye.z))
      throw std::invalid_argument("the eye position must be finite");
  } else if (!(glm::length(view.direction) > 0.0) || !std::isfinite(glm::length(view.direction))) {
    throw std::invalid_argument("the viewing direction must be a finite non-zero vector");
  }
}

}  // namespace

SilhouetteResult extract_silhouettes(const VolumeSpline& spline, const SingletonTable& table, double iso,
                                     const SilhouetteView& view, const SilhouetteParams& params) {
  check_params(iso, view, params);
  for (int a = 0; a < 3; ++a)
    if (table.cells()[a] != spline.span_count(a))
      throw std::invalid_argument("the singleton table was built for another volume spline");
  const auto t0 = std::chrono::steady_clock::now();
  SilhouetteResult result;
  const Problem pb{spline,
                   table,
                   index_view(spline, view),
                   iso,
                   std::max(spline.control_max() - spline.control_min(), 1e-30),
                   params.accuracy,
                   glm::dmat3(spline.index_to_world())};
  const IndexView& iv = pb.view;
  // The directions w can take over the grid box: one cone (axis, half-angle) for the bin filter.
  glm::dvec3 w_axis = iv.v;
  double w_half = 0.0;
  if (iv.perspective) {
    const glm::dvec3 hi(spline.dims()[0] - 1, spline.dims()[1] - 1, spline.dims()[2] - 1);
    const glm::dvec3 centre = hi * 0.5;
    const double radius = glm::length(hi) * 0.5 + 1.0;
    const glm::dvec3 d = centre - iv.eye;
    const double dist = glm::length(d);
    w_axis = dist > 0.0 ? d / dist : glm::dvec3(0.0, 0.0, 1.0);
    w_half = dist > radius ? std::asin(radius / dist) : kPi;
  }
  const std::vector<std::uint32_t> bins = table.cells_holding(iso, w_axis, w_half, SingletonTable::CellOrder::by_bin);
  // The candidates by block (in the table's order within a block: the bucketing is stable).
  const auto& dims = table.cells();
  const glm::ivec3 blocks((dims[0] + kBlock - 1) / kBlock, (dims[1] + kBlock - 1) / kBlock,
                          (dims[2] + kBlock - 1) / kBlock);
  const std::size_t block_count = static_cast<std::size_t>(blocks.x) * blocks.y * blocks.z;
  auto cell_coords = [&](std::uint32_t cell) {
    return glm::ivec3(static_cast<int>(cell % dims[0]), static_cast<int>((cell / dims[0]) % dims[1]),
                      static_cast<int>(cell / (static_cast<std::size_t>(dims[0]) * dims[1])));
  };
  auto block_of = [&](const glm::ivec3& c) {
    return static_cast<std::size_t>(c.x / kBlock) +
           blocks.x * (static_cast<std::size_t>(c.y / kBlock) + blocks.y * static_cast<std::size_t>(c.z / kBlock));
  };
  std::vector<std::uint32_t> block_begin(block_count + 1, 0), by_block(bins.size()), block_id(bins.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bins.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e) block_id[e] = static_cast<std::uint32_t>(block_of(cell_coords(bins[e])));
  });
  for (std::uint32_t b : block_id) ++block_begin[b + 1];
  for (std::size_t b = 0; b < block_count; ++b) block_begin[b + 1] += block_begin[b];
  {
    std::vector<std::uint32_t> fill(block_begin.begin(), block_begin.end() - 1);
    for (std::size_t e = 0; e < bins.size(); ++e) by_block[fill[block_id[e]]++] = bins[e];
  }
  // Each block: the exact per-singleton cone test (cell-sized view cone in perspective), then seeds, Newton and
  // tracing, skipping cells a trace has already crossed. Blocks write to their own slots (deterministic for any
  // thread count).
  std::vector<std::vector<Trace>> block_traces(block_count);
  std::vector<std::size_t> cand(block_count, 0), seeds(block_count, 0);
  const auto& singles = table.singletons();
  tbb::enumerable_thread_specific<BlockScratch> scratch;
#if defined(__SSE2__)
  std::optional<CubicHullTest> cubic;
  if (spline.order() == 4) cubic.emplace(spline, iv);
#endif
  tbb::parallel_for(std::size_t(0), block_count, [&](std::size_t blk) {
    if (block_begin[blk] == block_begin[blk + 1]) return;
    const glm::ivec3 bc(static_cast<int>(blk % blocks.x), static_cast<int>((blk / blocks.x) % blocks.y),
                        static_cast<int>(blk / (static_cast<std::size_t>(blocks.x) * blocks.y)));
    const glm::ivec3 first = bc * kBlock;
    const glm::ivec3 last = glm::min(first + kBlock, glm::ivec3(dims[0], dims[1], dims[2]));
    BlockTracer tracer(pb, first, last, scratch.local());
    for (std::uint32_t e = block_begin[blk]; e < block_begin[blk + 1]; ++e) {
      // The singletons are read in bin order, far apart in memory: fetch a few ahead.
      if (e + 8 < block_begin[blk + 1]) __builtin_prefetch(&singles[by_block[e + 8]]);
      const std::uint32_t cell = by_block[e];
      const glm::ivec3 c = cell_coords(cell);
      if (tracer.visited(c)) continue;
      const Singleton& s = singles[cell];
      glm::dvec3 w = iv.v;
      double s_w = 0.0, c_w = 1.0;
      if (iv.perspective) {
        const glm::dvec3 centre(spline.span_begin(c.x) + 0.5, spline.span_begin(c.y) + 0.5,
                                spline.span_begin(c.z) + 0.5);
        w = centre - iv.eye;
        const double dist = glm::length(w);
        const double r = std::sqrt(3.0) * 0.5;
        if (dist <= r) {
          s_w = 1.0, c_w = 0.0;
        } else {
          w /= dist;
          s_w = r / dist, c_w = std::sqrt(1.0 - s_w * s_w);
        }
      }
      if (s_w < 1.0 && !cones_admit_orthogonal(s, w, s_w, c_w)) continue;
      ++cand[blk];
      const glm::dvec3 cell_lo(spline.span_begin(c.x), spline.span_begin(c.y), spline.span_begin(c.z));
      bool whole_cell_tested = false;
#if defined(__SSE2__)
      if (cubic) {
        if (!cubic->may_hold_zero(c.x, c.y, c.z)) continue;
        whole_cell_tested = true;
      }
#endif
      seed_cell(pb, c.x, c.y, c.z, params.subdivision, whole_cell_tested, [&](const glm::dvec3& centre) {
        ++seeds[blk];
        CurvePoint p;
        // A seed heading into a cell a trace has crossed is given up early (what it would find there is known).
        auto known = [&](const glm::dvec3& x) { return tracer.inside(x) && tracer.visited(tracer.cell_of(x)); };
        if (!solve_point(pb, centre, cell_lo - 0.5, cell_lo + 1.5, kSeedIterations, p, -1, known)) return false;
        // A converged point anywhere in the block starts a trace, unless a trace already passed there.
        if (!tracer.inside(p.x) || tracer.visited(tracer.cell_of(p.x)) || tracer.near_trace(p.x, kJoinRadius))
          return false;
        tracer.trace_from(p);
        return tracer.visited(c);  // this cell is covered: its other seeds would find the same curve
      });
    }
    block_traces[blk] = std::move(tracer.traces);
  });
  std::vector<Trace> traces;
  for (std::size_t b = 0; b < block_count; ++b) {
    result.candidates += cand[b];
    result.seeds += seeds[b];
    for (Trace& t : block_traces[b]) traces.push_back(std::move(t));
  }
  for (const Chain& chain : join_traces(traces)) {
    SilhouettePolyline pl;
    std::vector<const CurvePoint*> pts;
    for (const ChainPiece& piece : chain.pieces) {
      const auto& tp = traces[piece.trace].points;
      const std::size_t m = tp.size();
      // The first point of every piece after the first repeats the face point the previous piece ended on.
      for (std::size_t i = pts.empty() ? 0 : 1; i < m; ++i) pts.push_back(&tp[piece.reversed ? m - 1 - i : i]);
    }
    if (chain.closed && chain.pieces.size() > 1 && !pts.empty()) pts.pop_back();  // back at the first face point
    if (pts.size() < 2) continue;  // isolated points are not strokes of a curve
    pl.closed = chain.closed && pts.size() >= 3;
    const std::size_t n = pts.size();
    pl.points.reserve(n);
    pl.gradient_norm.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const CurvePoint& p = *pts[i];
      pl.points.push_back(glm::dvec3(spline.index_to_world() * glm::dvec4(p.x, 1.0)));
      pl.gradient_norm.push_back(p.gradient_norm);
      result.max_value_residual = std::max(result.max_value_residual, p.value_residual);
      result.max_dot_residual = std::max(result.max_dot_residual, p.dot_residual);
      if (i > 0) result.length_mm += glm::length(pl.points[i] - pl.points[i - 1]);
    }
    if (pl.closed) result.length_mm += glm::length(pl.points.front() - pl.points.back());
    pl.visible.assign(n, 1);
    result.points += n;
    result.polylines.push_back(std::move(pl));
  }
  result.extract_ms = ms_since(t0);
  if (params.hidden_test) {
    const auto t1 = std::chrono::steady_clock::now();
    // Every 4th point (and the last) is tested; the points between two tested ones of the same visibility take it,
    // those between two that differ are tested one by one. A visibility change is located exactly; only a hidden
    // stretch shorter than 4 points between two visible ones (or the reverse) could be missed.
    constexpr std::size_t kStride = 4;
    auto occluded = [&](const SilhouettePolyline& pl, std::size_t i) {
      const glm::dvec3 x(spline.world_to_index() * glm::dvec4(pl.points[i], 1.0));
      return iso_occluded(spline, table, iso, view, x) ? 0 : 1;
    };
    // The tested points of all polylines as one list (a few polylines hold most points: splitting by polyline would
    // leave one thread with the longest), then the stretches between two tested points that differ, per polyline.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> tested;  // (polyline, point)
    for (std::size_t k = 0; k < result.polylines.size(); ++k) {
      const std::size_t n = result.polylines[k].points.size();
      for (std::size_t i = 0; i < n; i += kStride) tested.emplace_back(std::uint32_t(k), std::uint32_t(i));
      if ((n - 1) % kStride != 0) tested.emplace_back(std::uint32_t(k), std::uint32_t(n - 1));
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tested.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t e = r.begin(); e != r.end(); ++e) {
        SilhouettePolyline& pl = result.polylines[tested[e].first];
        pl.visible[tested[e].second] = static_cast<unsigned char>(occluded(pl, tested[e].second));
      }
    });
    tbb::parallel_for(std::size_t(0), result.polylines.size(), [&](std::size_t k) {
      SilhouettePolyline& pl = result.polylines[k];
      const std::size_t n = pl.points.size();
      for (std::size_t prev = 0; prev + 1 < n;) {
        const std::size_t next = std::min(prev + kStride, n - 1);
        for (std::size_t i = prev + 1; i < next; ++i)
          pl.visible[i] = pl.visible[prev] == pl.visible[next] ? pl.visible[prev]
                                                                : static_cast<unsigned char>(occluded(pl, i));
        prev = next;
      }
    });
    result.hidden_ms = ms_since(t1);
  }
  return result;
}

bool iso_occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const SilhouetteView& view,
                  const glm::dvec3& from, double skip) {
  const IndexView iv = index_view(spline, view);
  glm::dvec3 dir = iv.perspective ? iv.eye - from : -iv.v;
  double t_end = iv.perspective ? glm::length(dir) : INFINITY;
  if (!(glm::length(dir) > 0.0)) return false;
  dir /= glm::length(dir);
  // Clip to the grid box.
  const glm::dvec3 hi(spline.dims()[0] - 1, spline.dims()[1] - 1, spline.dims()[2] - 1);
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 0.0) t_end = std::min(t_end, (hi[a] - from[a]) / dir[a]);
    else if (dir[a] < 0.0) t_end = std::min(t_end, (0.0 - from[a]) / dir[a]);
  }
  const double step = 0.4;
  double t = skip;
  if (!(t < t_end)) return false;
  double prev = spline.value(from + t * dir) - iso;
  const auto& md = table.macro_cells();
  const auto& cells = table.cells();
  const double shift = spline.span_begin(0);  // cell c starts at c + shift on every axis
  // Where the ray leaves the box of `size` index units starting at index `first`·size + shift on each axis.
  auto exit_of = [&](const int* first, double size) {
    double exit = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const double lo = first[a] * size + shift, up = lo + size;
      if (dir[a] > 0.0) exit = std::min(exit, (up - from[a]) / dir[a]);
      else if (dir[a] < 0.0) exit = std::min(exit, (lo - from[a]) / dir[a]);
    }
    return exit;
  };
  while (t < t_end) {
    // Skip macro-cells, then cells, whose range cannot hold the level: jump to where the ray leaves them. The sign of
    // D − c there is the box's (its whole range is on one side of c), so no value is needed.
    const glm::dvec3 x = from + t * dir;
    int m[3], c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = std::clamp(static_cast<int>(std::floor(x[a] - shift)), 0, cells[a] - 1);
      m[a] = std::min(c[a] / SingletonTable::kMacro, md[a] - 1);
    }
    const glm::vec2 r = table.macro_range(m[0], m[1], m[2]);
    if (!(double(r.x) <= iso && iso <= double(r.y))) {
      t = std::max(exit_of(m, SingletonTable::kMacro) + 1e-6, t + 1e-6);
      prev = double(r.y) < iso ? -1.0 : 1.0;
      continue;
    }
    const Singleton& sg = table.singletons()[table.cell_index(c[0], c[1], c[2])];
    if (!(double(sg.lo) <= iso && iso <= double(sg.hi))) {
      t = std::max(exit_of(c, 1.0) + 1e-6, t + 1e-6);
      prev = double(sg.hi) < iso ? -1.0 : 1.0;
      continue;
    }
    const double tn = std::min(t + step, t_end);
    const double f = spline.value(from + tn * dir) - iso;
    if ((prev < 0.0) != (f < 0.0)) return true;
    prev = f;
    t = tn;
    if (tn >= t_end) break;
  }
  return false;
}

}  // namespace trispline::core
