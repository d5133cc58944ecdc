// Internal to the silhouette extraction (silhouettes.cpp): the view in index space, Newton on Eq. 7.2, and the seeds
// of a candidate singleton (cone and hull tests, sub-cells). Not a public API.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <glm/glm.hpp>

#include "core/volume/bezier_cell.h"
#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_spline.h"

namespace trispline::core::silhouette_detail {

constexpr double kPi = 3.14159265358979323846;

// Curve tracing: steps of at most kStepMax index units, halved down to kStepMin where the corrector fails or the
// tangent turns by more than kMaxTurnDeg in one step.
constexpr double kStepMax = 0.5, kStepMin = 1.0 / 128.0, kMaxTurnDeg = 25.0;
// A march stops where it comes within kJoinRadius index units of a point already traced (a point on a chord of length
// kStepMax is within kStepMax/2 of one of its ends).
constexpr double kJoinRadius = 0.75 * kStepMax;
// A corrected point farther than kPredictorReach·h from the predicted one may lie on a neighbouring branch: the step
// is retried at h/2.
constexpr double kPredictorReach = 0.35;
// Where a cell covers only a few pixels (SilhouetteParams::pixel_step): steps of up to a cell that turn by up to 60°,
// and a corrected point may lie up to h/2 from the predicted one (a neighbouring branch that close is within a pixel
// or two on the screen; 0.35 rejected a third of the steps there).
constexpr double kCoarseStepMax = 1.0, kCoarseTurnDeg = 60.0, kCoarsePredictorReach = 0.5;

// How finely one block is traced: the longest step and the turn allowed in a step, the radius (≤ 1, index units)
// within which a march meets a point already traced, and how far (a fraction of the step) the corrector may move the
// predicted point.
struct TraceLimits {
  double step_max = kStepMax;
  double min_turn_cos = std::cos(kMaxTurnDeg * kPi / 180.0);
  double join_radius = kJoinRadius;
  double predictor_reach = kPredictorReach;

  static TraceLimits coarse() {
    return {kCoarseStepMax, std::cos(kCoarseTurnDeg * kPi / 180.0), 0.75 * kCoarseStepMax, kCoarsePredictorReach};
  }
};
constexpr int kCorrectorIterations = 8, kSeedIterations = 6, kMaxSteps = 1 << 16;
// Cells per block axis: blocks are traced independently (in parallel) and their traces joined at the block faces.
constexpr int kBlock = 16;
// Cells per tile axis of the hidden-cell test's first answer (BlockTracer::hidden); divides kBlock.
constexpr int kHiddenTile = 4;

// The view in index space: the silhouette condition G·V = 0 in world coordinates is g·w = 0 with g the index-space
// gradient and w = A⁻¹V (orthographic) or x − eye_index (perspective), A the linear part of index_to_world.
struct IndexView {
  bool perspective = true;
  glm::dvec3 eye{0.0};  // index space
  glm::dvec3 v{0.0};    // index space, unit (orthographic)
  glm::dvec3 w(const glm::dvec3& x) const { return perspective ? x - eye : v; }
};

inline IndexView index_view(const VolumeSpline& spline, const SilhouetteView& view) {
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

class HiddenCells;
class LevelSides;

// What every solve needs: the spline, the level, the view and the stopping accuracy.
struct Problem {
  const VolumeSpline& spline;
  const SingletonTable& table;
  IndexView view;
  double iso = 0.0;
  double range = 1.0;  // range(D) for the relative value residual
  double accuracy = 1e-7;
  glm::dmat3 to_world{1.0};  // linear part of index_to_world
  // SilhouetteParams::seed_hidden false: the cells the surface hides (they seed nothing, and a trace ends there).
  const HiddenCells* hidden = nullptr;
  const LevelSides* sides = nullptr;  // the cells' sides of `iso` (SilhouetteSequence), for the rays
};

// The first crossing of D = iso along from + t·dir, t in [t, t_end] (dir unit, index space), marched in steps of 0.4
// index units through the cells that can hold the level (the table's macro-cells and singletons skip the rest): the
// parameter of the first sample past the crossing (so at or beyond it), or −1 when there is none.
// `sides`, when given, holds the table's cells' sides of this level (LevelSides): the same answers from 1/96 of the
// memory the singletons take, so a ray's cell tests hit the cache, and tiles of cells on one side are skipped whole.
double first_crossing(const VolumeSpline& spline, const SingletonTable& table, double iso, const glm::dvec3& from,
                      const glm::dvec3& dir, double t, double t_end, const LevelSides* sides = nullptr);

// Whether the segment from `from` towards the eye crosses D = iso past `skip` index units (iso_occluded in index
// space).
bool occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const IndexView& iv,
              const glm::dvec3& from, double skip, const LevelSides* sides);

// Where each cell's value range lies with respect to one level: 2 bits a cell, filed by tiles of 4³ cells (a tile is
// two 64-bit words), so that a ray in any direction finds its next cells in the cache line it has just read, and a
// tile whose cells all lie on one side is crossed in one step.
class LevelSides {
 public:
  enum Side : unsigned { holds = 0, below = 1, above = 2 };
  static constexpr int kTile = 4;  // cells per tile axis

  LevelSides(const SingletonTable& table, double iso);
  double iso() const { return iso_; }
  // Cell (x, y, z), each within the table's cell counts.
  Side side(int x, int y, int z) const {
    const std::size_t t = tile_of(x, y, z);
    const unsigned k = unsigned(x & 3) + 4u * (unsigned(y & 3) + 4u * unsigned(z & 3));
    return Side((words_[2 * t + (k >> 5)] >> (2 * (k & 31))) & 3u);
  }
  // The side all cells of the tile holding cell (x, y, z) lie on, or holds when they differ (or some cell holds).
  Side tile_side(int x, int y, int z) const {
    const std::size_t t = tile_of(x, y, z);
    const std::uint64_t a = words_[2 * t], b = words_[2 * t + 1];
    if (a == kAllBelow && b == kAllBelow) return below;
    if (a == kAllAbove && b == kAllAbove) return above;
    return holds;
  }

 private:
  static constexpr std::uint64_t kAllBelow = 0x5555555555555555ull, kAllAbove = 0xAAAAAAAAAAAAAAAAull;
  std::size_t tile_of(int x, int y, int z) const {
    return std::size_t(x >> 2) + tiles_[0] * (std::size_t(y >> 2) + tiles_[1] * std::size_t(z >> 2));
  }
  double iso_;
  std::size_t tiles_[3] = {0, 0, 0};
  std::vector<std::uint64_t> words_;  // per tile: cells k = x + 4y + 16z (local), k < 32 in the first word
};

// The cells the iso-surface hides from the eye (SilhouetteParams::seed_hidden = false): the first crossing of
// D = iso along kN × kN rays — perspective: from the eye over the cone (axis, half-angle < 90°) that holds the grid
// box; orthographic: parallel to the view over the disc that holds it — and a cell is hidden when its nearest point
// lies more than kMargin beyond the farthest crossing over the map pixels its bounding sphere covers, plus one pixel
// around (a ray that misses counts as infinitely far).
class HiddenCells {
 public:
  static constexpr int kN = 128;
  static constexpr double kMargin = 4.0;  // index units

  // The map for `pb`'s view; `axis`, `half_angle`: the cone of directions from the eye that holds the grid box
  // (perspective; a half-angle near 90° or more, the eye inside or beside the box, makes no map: usable() false).
  HiddenCells(const Problem& pb, const glm::dvec3& axis, double half_angle);

  bool usable() const { return !depth_.empty(); }

  // Cells first…last − 1 per axis (a cell, or a block of them).
  bool hides(const glm::ivec3& first, const glm::ivec3& last) const {
    const glm::dvec3 lo(pb_.spline.span_begin(first.x), pb_.spline.span_begin(first.y), pb_.spline.span_begin(first.z));
    const glm::dvec3 size(last - first);
    return hides(lo + 0.5 * size, 0.5 * glm::length(size));
  }

  // The ball of radius r (index units) around c.
  bool hides(const glm::dvec3& c, double r) const {
    const glm::dvec3 d = c - origin_;
    const double s = glm::dot(d, a_);
    double px, py, pr, near;
    if (pb_.view.perspective) {
      if (!(s > 2.0 * r + 1.0)) return false;
      px = glm::dot(d, u_) / s, py = glm::dot(d, v_) / s;
      // The sphere's footprint in the tangent plane: its angular radius, widened by the plane's stretch off axis.
      pr = r / (s - r) * (1.0 + px * px + py * py);
      near = glm::length(d) - r;
    } else {
      px = glm::dot(d, u_), py = glm::dot(d, v_), pr = r, near = s - r;
    }
    const double to_pixel = 0.5 * kN / scale_;
    const int i0 = int(std::floor((px - pr) * to_pixel + 0.5 * kN)) - 1,
              i1 = int(std::floor((px + pr) * to_pixel + 0.5 * kN)) + 1;
    const int j0 = int(std::floor((py - pr) * to_pixel + 0.5 * kN)) - 1,
              j1 = int(std::floor((py + pr) * to_pixel + 0.5 * kN)) + 1;
    if (i0 < 0 || j0 < 0 || i1 >= kN || j1 >= kN) return false;  // at the map's edge: seen, for all we know
    double farthest = 0.0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) farthest = std::max(farthest, depth_[std::size_t(j) * kN + std::size_t(i)]);
    // Perspective rays measure distance from the eye; orthographic ones depth along the view from the origin plane.
    return near > farthest + kMargin;
  }

 private:
  const Problem& pb_;
  glm::dvec3 a_{0.0}, u_{0.0}, v_{0.0}, origin_{0.0};
  double scale_ = 1.0;         // tangent (perspective) or distance (orthographic) at the map's edge
  std::vector<double> depth_;  // kN × kN first crossings, row j then column i; +∞: none
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
inline bool solve_point(const Problem& pb, glm::dvec3 x, const glm::dvec3& lo, const glm::dvec3& hi, int iterations,
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
inline bool cones_admit_orthogonal(const Singleton& s, const glm::dvec3& w, double s_w, double c_w) {
  const double sa = s.sin_half;
  if (sa >= 1.0) return true;
  const double ca = std::sqrt(std::max(0.0, 1.0 - sa * sa));
  const double sin_sum = sa * c_w + ca * s_w;   // sin(α + γ)
  if (ca * c_w - sa * s_w <= 0.0) return true;  // α + γ ≥ 90°
  const double d = std::abs(double(s.axis[0]) * w.x + double(s.axis[1]) * w.y + double(s.axis[2]) * w.z);
  return d <= sin_sum;
}

// Range of G·w over a (sub-)cell from its Bézier coefficients: the hull of the gradient's vector coefficients dotted
// with w (orthographic), or with w at the centre plus the largest change of w over the box (perspective:
// g·(x − eye) = g·(centre − eye) + g·(x − centre), |x − centre| ≤ (√3/2)·h). `h`: the box's side in index units (the
// coefficients' local unit). Returns false when 0 is outside the range.
template <int K>
inline bool dot_range_holds_zero(const double* coefs, const glm::dvec3& centre, const IndexView& view) {
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
// raised derivative coefficients (≲ 12 ulp of max|P| per coefficient, times 6 for the differences), so a cell it
// rejects would be rejected in double precision too; a cell it passes goes on to the exact tests.
class CubicHullTest {
 public:
  CubicHullTest(const VolumeSpline& spline, const IndexView& view)
      : spline_(spline),
        view_(view),
        max_abs_(std::max(std::abs(spline.control_min()), std::abs(spline.control_max()))) {
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
    const glm::dvec3 wc =
        view_.w(glm::dvec3(spline_.span_begin(a), spline_.span_begin(b), spline_.span_begin(c)) + 0.5);
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
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0)), column_[0]),
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
inline const std::array<bezier_cell::Matrix<K>, 4>& restrictions(int s) {
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
inline void seed_cell(const Problem& pb, int a, int b, int c, int subdivision, bool whole_cell_tested, Seed&& seed) {
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
  // The coefficients of sub-interval i of `axis` (restricted; the whole cell when s = 1), and — when `test` — whether
  // they can hold the iso-level (the sub-cell is skipped when not).
  auto part = [&](int i, const double* from, double* to, int axis, bool test) {
    if (s > 1)
      bezier_cell::apply<K>(restrict[i], from, to, axis);
    else
      std::copy(from, from + n, to);
    return !test || holds_iso(to);
  };
  double zslab[n], yrow[n], sub[n];
  for (int sz = 0; sz < s; ++sz) {
    if (!part(sz, bez, zslab, 2, s > 1)) continue;
    for (int sy = 0; sy < s; ++sy) {
      if (!part(sy, zslab, yrow, 1, s > 1)) continue;
      for (int sx = 0; sx < s; ++sx) {
        if (!part(sx, yrow, sub, 0, true)) continue;
        const glm::dvec3 centre = origin + glm::dvec3(sx + 0.5, sy + 0.5, sz + 0.5) * h;
        if (s > 1 && !dot_range_holds_zero<K>(sub, centre, pb.view)) continue;
        if (seed(centre)) return;
      }
    }
  }
}

template <class Seed>
inline void seed_cell(const Problem& pb, int a, int b, int c, int subdivision, bool whole_cell_tested, Seed&& seed) {
  switch (pb.spline.order()) {
    case 2:
      return seed_cell<2>(pb, a, b, c, subdivision, whole_cell_tested, seed);
    case 3:
      return seed_cell<3>(pb, a, b, c, subdivision, whole_cell_tested, seed);
    default:
      return seed_cell<4>(pb, a, b, c, subdivision, whole_cell_tested, seed);
  }
}

}  // namespace trispline::core::silhouette_detail
