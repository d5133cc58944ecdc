#include "core/volume/silhouettes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/volume/bezier_cell.h"

namespace trispline::core {

namespace {

constexpr double kPi = 3.14159265358979323846;

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

struct Point {
  glm::dvec3 x;           // index space
  glm::dvec3 tangent;     // index space, unit
  std::uint32_t cell;     // the singleton it was found in
  float gradient_norm;    // per millimetre
  double value_residual;  // |D − c| / range
  double dot_residual;    // |Ĝ·V̂| in world space
};

// Newton–Raphson on F(x) = (D(x) − c, ∇D(x)·w(x)) = 0 (seed Eq. 7.2) with minimum-norm steps −Jᵀ(JJᵀ)⁻¹F.
// Returns false when it does not converge within the iteration budget or leaves `lo`…`hi`.
bool newton_silhouette(const VolumeSpline& spline, const IndexView& view, double iso, double range, double accuracy,
                       const glm::dvec3& lo, const glm::dvec3& hi, glm::dvec3& x, Point& out) {
  for (int it = 0; it < 12; ++it) {
    const VolumeJet j = spline.jet(x);
    const glm::dvec3 w = view.w(x);
    const double f1 = j.value - iso, f2 = glm::dot(j.gradient, w);
    const glm::dvec3 gw = spline.world_gradient(j.gradient);
    const glm::dvec3 ww = view.perspective ? glm::dmat3(spline.index_to_world()) * w
                                           : glm::dmat3(spline.index_to_world()) * view.v;
    const double gl = glm::length(gw), wl = glm::length(ww);
    if (!(gl > 0.0) || !(wl > 0.0)) return false;
    const double value_res = std::abs(f1) / range, dot_res = std::abs(glm::dot(gw, ww)) / (gl * wl);
    if (value_res <= accuracy && dot_res <= accuracy) {
      out.x = x;
      out.value_residual = value_res;
      out.dot_residual = dot_res;
      out.gradient_norm = static_cast<float>(gl);
      const glm::dvec3 r2 = j.hessian * w + (view.perspective ? j.gradient : glm::dvec3(0.0));
      const glm::dvec3 t = glm::cross(j.gradient, r2);
      const double tl = glm::length(t);
      out.tangent = tl > 0.0 ? t / tl : glm::dvec3(0.0);
      return true;
    }
    const glm::dvec3 r1 = j.gradient;
    const glm::dvec3 r2 = j.hessian * w + (view.perspective ? j.gradient : glm::dvec3(0.0));
    const double a = glm::dot(r1, r1), b = glm::dot(r1, r2), c = glm::dot(r2, r2);
    const double det = a * c - b * b;
    if (!(det > 1e-300) || !(std::abs(det) > 1e-14 * a * c)) return false;
    const double l1 = (c * f1 - b * f2) / det, l2 = (a * f2 - b * f1) / det;
    glm::dvec3 step = -(l1 * r1 + l2 * r2);
    const double sl = glm::length(step);
    if (!std::isfinite(sl)) return false;
    if (sl > 0.5) step *= 0.5 / sl;
    x += step;
    if (glm::any(glm::lessThan(x, lo)) || glm::any(glm::greaterThan(x, hi))) return false;
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
bool dot_range_holds_zero(const double* coefs, const glm::dvec3& centre, double h, const IndexView& view) {
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

// Seeds of one candidate singleton: its sub-cells whose value range holds c and whose range of G·w holds 0; each seeds
// Newton from its centre. Converged points inside the singleton (closed box) are appended.
template <int K>
void solve_singleton(const VolumeSpline& spline, const SingletonTable& table, std::uint32_t cell, double iso,
                     double range, const IndexView& view, const SilhouetteParams& params, std::vector<Point>& out,
                     std::size_t& seeds) {
  constexpr int n = K * K * K;
  const auto& dims = table.cells();
  const int a = static_cast<int>(cell % dims[0]);
  const int b = static_cast<int>((cell / dims[0]) % dims[1]);
  const int c = static_cast<int>(cell / (static_cast<std::size_t>(dims[0]) * dims[1]));
  double bez[n];
  spline.bezier_coefficients(a, b, c, bez);
  const glm::dvec3 origin(spline.span_begin(a), spline.span_begin(b), spline.span_begin(c));
  // The whole singleton first: its G·w hull must hold 0 before any sub-cell is made.
  if (!dot_range_holds_zero<K>(bez, origin + 0.5, 1.0, view)) return;
  glm::dvec3 domain_hi;
  for (int ax = 0; ax < 3; ++ax) domain_hi[ax] = spline.dims()[ax] - 1;
  // Converged points must lie in this singleton's box clipped to the domain (a point on a shared face may be found
  // twice; duplicates are merged when the polylines are made).
  const glm::dvec3 box_lo = glm::max(origin, glm::dvec3(0.0)), box_hi = glm::min(origin + 1.0, domain_hi);
  const int s = params.subdivision;
  const double h = 1.0 / s;
  bezier_cell::Matrix<K> restrict[4];
  for (int i = 0; i < s; ++i) restrict[i] = bezier_cell::restriction<K>(i * h, (i + 1) * h);
  const std::size_t first_out = out.size();
  auto holds_iso = [iso](const double* c) {
    double mn = c[0], mx = c[0];
    for (int m = 1; m < n; ++m) mn = std::min(mn, c[m]), mx = std::max(mx, c[m]);
    return mn <= iso && iso <= mx;
  };
  // Sub-cells by slabs: z first, then y within a surviving slab, then x — a slab whose value range misses c is not
  // split further (the sub-boxes of a slab hold subsets of its range).
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
        const glm::dvec3 lo(sx * h, sy * h, sz * h);
        const glm::dvec3 centre = origin + lo + 0.5 * h;
        if (s > 1 && !dot_range_holds_zero<K>(sub, centre, h, view)) continue;
        ++seeds;
        glm::dvec3 x = centre;
        Point p;
        if (!newton_silhouette(spline, view, iso, range, params.accuracy, box_lo - 1.0, box_hi + 1.0, x, p)) continue;
        if (glm::any(glm::lessThan(p.x, box_lo)) || glm::any(glm::greaterThan(p.x, box_hi))) continue;
        bool duplicate = false;
        for (std::size_t q = first_out; q < out.size() && !duplicate; ++q)
          duplicate = glm::length(out[q].x - p.x) < 0.05 * h;
        if (duplicate) continue;
        p.cell = cell;
        out.push_back(p);
      }
    }
  }
}

void solve_singleton(const VolumeSpline& spline, const SingletonTable& table, std::uint32_t cell, double iso,
                     double range, const IndexView& view, const SilhouetteParams& params, std::vector<Point>& out,
                     std::size_t& seeds) {
  switch (spline.order()) {
    case 2: return solve_singleton<2>(spline, table, cell, iso, range, view, params, out, seeds);
    case 3: return solve_singleton<3>(spline, table, cell, iso, range, view, params, out, seeds);
    default: return solve_singleton<4>(spline, table, cell, iso, range, view, params, out, seeds);
  }
}

// Joins points into polylines: each point links to the nearest point ahead of it along its tangent and the nearest
// behind (within 2.5 index units, in the 5×5×5 block of cells around it, within 60° of the tangent line); a link is
// kept when both ends chose each other, so every point has at most two links and the pieces are paths or cycles.
std::vector<std::vector<std::uint32_t>> link_points(const std::vector<Point>& pts, const SingletonTable& table) {
  const auto& dims = table.cells();
  const std::size_t count = pts.size();
  const double reach = 2.5, min_cos = std::cos(60.0 * kPi / 180.0);
  // A hash grid of 4×4×4-cell blocks: the 5×5×5 cells around a point lie in at most 2×2×2 blocks.
  constexpr int kBlock = 4;
  const std::uint64_t bx = (dims[0] + kBlock - 1) / kBlock, by = (dims[1] + kBlock - 1) / kBlock;
  auto block_of = [&](const glm::dvec3& x) {
    auto q = [](double v) { return static_cast<std::int64_t>(std::floor(v / kBlock)); };
    return glm::i64vec3(q(x.x), q(x.y), q(x.z));
  };
  auto block_key = [&](std::int64_t i, std::int64_t j, std::int64_t l) {
    return static_cast<std::uint64_t>(i + 1) + (bx + 2) * (static_cast<std::uint64_t>(j + 1) +
                                                           (by + 2) * static_cast<std::uint64_t>(l + 1));
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto b = block_of(pts[i].x);
    keyed[i] = {block_key(b.x, b.y, b.z), static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  auto block_range = [&](std::uint64_t key) {
    auto lo = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, std::uint32_t(0)));
    auto hi = lo;
    while (hi != keyed.end() && hi->first == key) ++hi;
    return std::make_pair(lo, hi);
  };
  // Merge points closer than 0.02 index units (one found from each side of a shared face).
  std::vector<char> dead(count, 0);
  std::vector<std::array<std::int64_t, 2>> choice(count, {-1, -1});
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) {
    const Point& p = pts[i];
    double best[2] = {INFINITY, INFINITY};
    const auto b0 = block_of(p.x - reach), b1 = block_of(p.x + reach);
    for (std::int64_t l = b0.z; l <= b1.z; ++l)
      for (std::int64_t j = b0.y; j <= b1.y; ++j)
        for (std::int64_t k = b0.x; k <= b1.x; ++k) {
          const auto [q0, q1] = block_range(block_key(k, j, l));
          for (auto it = q0; it != q1; ++it) {
            const std::size_t q = it->second;
            if (q == i) continue;
            const glm::dvec3 d = pts[q].x - p.x;
            const double len = glm::length(d);
            if (len < 0.02) {
              if (q < i) dead[i] = 1;
              continue;
            }
            if (len > reach) continue;
            const double cosang = glm::dot(d, p.tangent) / len;
            const int side = cosang >= min_cos ? 0 : (cosang <= -min_cos ? 1 : -1);
            if (side < 0) continue;
            if (len < best[side] || (len == best[side] && static_cast<std::int64_t>(q) < choice[i][side]))
              best[side] = len, choice[i][side] = static_cast<std::int64_t>(q);
          }
        }
  });
  // Dead points' choices are dropped; others' choices of dead points are redirected by not linking them.
  std::vector<std::array<std::int64_t, 2>> links(count, {-1, -1});
  auto chose = [&](std::size_t i, std::int64_t q) { return choice[i][0] == q || choice[i][1] == q; };
  for (std::size_t i = 0; i < count; ++i) {
    if (dead[i]) continue;
    int n = 0;
    for (int side = 0; side < 2; ++side) {
      const std::int64_t q = choice[i][side];
      if (q < 0 || dead[q] || !chose(static_cast<std::size_t>(q), static_cast<std::int64_t>(i))) continue;
      links[i][n++] = q;
    }
  }
  // Walk: start at ends (one link or none) in index order, then the remaining cycles.
  std::vector<char> used(count, 0);
  std::vector<std::vector<std::uint32_t>> chains;
  auto walk = [&](std::size_t start) {
    std::vector<std::uint32_t> chain;
    std::int64_t prev = -1, cur = static_cast<std::int64_t>(start);
    while (cur >= 0 && !used[cur]) {
      used[cur] = 1;
      chain.push_back(static_cast<std::uint32_t>(cur));
      std::int64_t next = -1;
      for (std::int64_t q : links[cur])
        if (q >= 0 && q != prev && !used[q]) { next = q; break; }
      prev = cur, cur = next;
    }
    return chain;
  };
  for (std::size_t i = 0; i < count; ++i)
    if (!dead[i] && !used[i] && (links[i][0] < 0 || links[i][1] < 0)) chains.push_back(walk(i));
  for (std::size_t i = 0; i < count; ++i)
    if (!dead[i] && !used[i]) {
      auto chain = walk(i);
      chain.push_back(chain.front());  // a cycle: closed (marked by repeating the first point, removed by the caller)
      chains.push_back(std::move(chain));
    }
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
  const IndexView iv = index_view(spline, view);
  const double range = std::max(spline.control_max() - spline.control_min(), 1e-30);
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
  const std::vector<std::uint32_t> bins = table.cells_holding(iso, w_axis, w_half);
  // Exact per-singleton tests (cell-sized view cone in perspective), then seeds and Newton, in fixed chunks whose
  // outputs are concatenated in order (deterministic for any thread count).
  const std::size_t chunk = 256, chunks = (bins.size() + chunk - 1) / chunk;
  std::vector<std::vector<Point>> outs(chunks);
  std::vector<std::size_t> cand(chunks, 0), seeds(chunks, 0);
  const auto& singles = table.singletons();
  const auto& dims = table.cells();
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t ch) {
    for (std::size_t e = ch * chunk; e < std::min(bins.size(), (ch + 1) * chunk); ++e) {
      const std::uint32_t cell = bins[e];
      const Singleton& s = singles[cell];
      glm::dvec3 w = iv.v;
      double s_w = 0.0, c_w = 1.0;
      if (iv.perspective) {
        const int a = static_cast<int>(cell % dims[0]);
        const int b = static_cast<int>((cell / dims[0]) % dims[1]);
        const int c = static_cast<int>(cell / (static_cast<std::size_t>(dims[0]) * dims[1]));
        const glm::dvec3 centre(spline.span_begin(a) + 0.5, spline.span_begin(b) + 0.5, spline.span_begin(c) + 0.5);
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
      ++cand[ch];
      solve_singleton(spline, table, cell, iso, range, iv, params, outs[ch], seeds[ch]);
    }
  });
  std::vector<Point> pts;
  for (std::size_t ch = 0; ch < chunks; ++ch) {
    result.candidates += cand[ch];
    result.seeds += seeds[ch];
    pts.insert(pts.end(), outs[ch].begin(), outs[ch].end());
  }
  const auto chains = link_points(pts, table);
  for (const auto& chain : chains) {
    SilhouettePolyline pl;
    std::size_t n = chain.size();
    if (n >= 3 && chain.front() == chain.back()) pl.closed = true, --n;
    if (n < 2) continue;  // isolated points are not strokes of a curve
    pl.points.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Point& p = pts[chain[i]];
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
    tbb::parallel_for(std::size_t(0), result.polylines.size(), [&](std::size_t k) {
      SilhouettePolyline& pl = result.polylines[k];
      const std::size_t n = pl.points.size();
      std::size_t prev = 0;
      pl.visible[0] = static_cast<unsigned char>(occluded(pl, 0));
      for (std::size_t next = std::min(kStride, n - 1); prev < n - 1; prev = next, next = std::min(next + kStride, n - 1)) {
        pl.visible[next] = static_cast<unsigned char>(occluded(pl, next));
        for (std::size_t i = prev + 1; i < next; ++i)
          pl.visible[i] = pl.visible[prev] == pl.visible[next] ? pl.visible[prev]
                                                                : static_cast<unsigned char>(occluded(pl, i));
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
  const double shift = spline.span_begin(0);  // cell c starts at c + shift on every axis
  while (t < t_end) {
    // Skip macro-cells whose range cannot hold the level: jump to where the ray leaves the macro-cell.
    const glm::dvec3 x = from + t * dir;
    int m[3];
    for (int a = 0; a < 3; ++a)
      m[a] = std::clamp(static_cast<int>(std::floor((x[a] - shift) / SingletonTable::kMacro)), 0, md[a] - 1);
    const glm::vec2 r = table.macro_range(m[0], m[1], m[2]);
    if (!(double(r.x) <= iso && iso <= double(r.y))) {
      double exit = INFINITY;
      for (int a = 0; a < 3; ++a) {
        const double lo = m[a] * SingletonTable::kMacro + shift, up = lo + SingletonTable::kMacro;
        if (dir[a] > 0.0) exit = std::min(exit, (up - from[a]) / dir[a]);
        else if (dir[a] < 0.0) exit = std::min(exit, (lo - from[a]) / dir[a]);
      }
      t = std::max(exit + 1e-6, t + 1e-6);
      if (t >= t_end) break;
      prev = spline.value(from + t * dir) - iso;
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
