#include "core/ffd/deformation_bounds.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "core/base/enum_names.h"

namespace trispline::core {

namespace {

// The smallest upper bound on max_{|v|=1} |v|ᵀ M |v| this code can give cheaply for a non-negative symmetric M: the
// largest eigenvalue (Perron) is at most both the largest row sum and the Frobenius norm.
double direction_bound(const glm::dmat3& m) {
  double rows = 0.0, frob = 0.0;
  for (int a = 0; a < 3; ++a) {
    rows = std::max(rows, m[a][0] + m[a][1] + m[a][2]);
    for (int b = 0; b < 3; ++b) frob += m[a][b] * m[a][b];
  }
  return std::min(rows, std::sqrt(frob));
}

// Per second partial (uu, vv, ww, uv, uw, vw), the component-wise box of its Bézier control points.
struct CellHull {
  glm::dvec3 lo[6], hi[6];
  bool any[6] = {};
  void add(int e, const glm::dvec3& d) {
    lo[e] = any[e] ? glm::min(lo[e], d) : d;
    hi[e] = any[e] ? glm::max(hi[e], d) : d;
    any[e] = true;
  }
  void scale(int e, double s) { lo[e] *= s, hi[e] *= s; }  // s > 0
  void store(std::array<double, 36>& out) const {
    for (int e = 0; e < 6; ++e) {
      const glm::dvec3 c = any[e] ? 0.5 * (lo[e] + hi[e]) : glm::dvec3(0.0);
      // Half-widths rounded outward by a few ulps so that |c·n| + Σ|n_i|h_i never falls below a hull point's |d·n|.
      const glm::dvec3 h = any[e] ? 0.5 * (hi[e] - lo[e]) * (1.0 + 1e-14) + 1e-300 : glm::dvec3(0.0);
      for (int i = 0; i < 3; ++i) out[6 * e + i] = c[i], out[6 * e + 3 + i] = h[i];
    }
  }
};

// A Bézier net of degrees deg, (deg+1)³ points, x fastest.
using Net = std::vector<glm::dvec3>;

std::size_t net_index(const glm::ivec3& deg, int i, int j, int k) {
  return i + static_cast<std::size_t>(deg.x + 1) * (j + static_cast<std::size_t>(deg.y + 1) * k);
}

// Bounds of the second partials of the Bézier trivariate `P` (degrees deg) over a box of parameter size `size`: the
// second differences of its control points times p(p−1)/Δ² (pure) or p·q/(Δa·Δb) (mixed) — the control points of the
// partials' own Bézier forms, so their norms and component boxes bound them (convex hull property).
SecondDerivativeBounds::BoxBound bound_net(const Net& P, const glm::ivec3& deg, const glm::dvec3& size) {
  SecondDerivativeBounds::BoxBound out;
  CellHull hull;
  auto at = [&](const glm::ivec3& q) -> const glm::dvec3& { return P[net_index(deg, q.x, q.y, q.z)]; };
  for (int a = 0; a < 3; ++a) {
    if (deg[a] < 2) continue;
    double mx = 0.0;
    for (int k = 0; k <= deg.z; ++k)
      for (int j = 0; j <= deg.y; ++j)
        for (int i = 0; i <= deg.x; ++i) {
          glm::ivec3 q(i, j, k);
          if (q[a] + 2 > deg[a]) continue;
          glm::ivec3 q1 = q, q2 = q;
          q1[a] += 1, q2[a] += 2;
          const glm::dvec3 d = at(q2) - 2.0 * at(q1) + at(q);
          mx = std::max(mx, glm::dot(d, d));  // squared: one square root at the end
          hull.add(a, d);
        }
    const double s = deg[a] * (deg[a] - 1) / (size[a] * size[a]);
    out.m[a] = s * std::sqrt(mx);
    hull.scale(a, s);
  }
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int e = 0; e < 3; ++e) {
    const int a = pairs[e][0], b = pairs[e][1];
    double mx = 0.0;
    for (int k = 0; k <= deg.z; ++k)
      for (int j = 0; j <= deg.y; ++j)
        for (int i = 0; i <= deg.x; ++i) {
          const glm::ivec3 q(i, j, k);
          if (q[a] + 1 > deg[a] || q[b] + 1 > deg[b]) continue;
          glm::ivec3 qa = q, qb = q, qab = q;
          qa[a] += 1, qb[b] += 1, qab[a] += 1, qab[b] += 1;
          const glm::dvec3 d = at(qab) - at(qa) - at(qb) + at(q);
          mx = std::max(mx, glm::dot(d, d));  // squared: one square root at the end
          hull.add(3 + e, d);
        }
    const double s = deg[a] * deg[b] / (size[a] * size[b]);
    out.m[3 + e] = s * std::sqrt(mx);
    hull.scale(3 + e, s);
  }
  hull.store(out.box);
  return out;
}

// The two halves of `P` along `axis` (de Casteljau at ½): the same function on each half of the box.
std::pair<Net, Net> halve(const Net& P, const glm::ivec3& deg, int axis) {
  Net lo(P.size()), hi(P.size());
  const int n = deg[axis];
  std::vector<glm::dvec3> row(static_cast<std::size_t>(n + 1));
  glm::ivec3 q(0);
  glm::ivec3 span = deg;
  span[axis] = 0;
  for (q.z = 0; q.z <= span.z; ++q.z)
    for (q.y = 0; q.y <= span.y; ++q.y)
      for (q.x = 0; q.x <= span.x; ++q.x) {
        glm::ivec3 r = q;
        for (int t = 0; t <= n; ++t) r[axis] = t, row[t] = P[net_index(deg, r.x, r.y, r.z)];
        for (int level = 0; level <= n; ++level) {
          r[axis] = level;
          lo[net_index(deg, r.x, r.y, r.z)] = row[0];
          r[axis] = n - level;
          hi[net_index(deg, r.x, r.y, r.z)] = row[n - level];
          for (int t = 0; t + level < n; ++t) row[t] = 0.5 * (row[t] + row[t + 1]);
        }
      }
  return {std::move(lo), std::move(hi)};
}

// Quadratic forms of the three edges for a bound matrix M (non-negative, symmetric) and the bound of the chosen method.
double bound_from_matrix(const glm::dmat3& M, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                         ErrorBound method) {
  // |e|ᵀ M |e′| for the three edges (signs do not matter: absolute values), then the right angle at each vertex:
  // at c the legs are ca and cb, at a ab and ac, at b bc and ba.
  const glm::dvec3 e[3] = {glm::abs(a - c), glm::abs(b - c), glm::abs(b - a)};  // ca, cb, ab
  glm::dvec3 me[3];
  for (int i = 0; i < 3; ++i) me[i] = M * e[i];  // M is symmetric
  const double q00 = glm::dot(e[0], me[0]), q11 = glm::dot(e[1], me[1]), q22 = glm::dot(e[2], me[2]);
  const double q01 = glm::dot(e[0], me[1]), q02 = glm::dot(e[0], me[2]), q12 = glm::dot(e[1], me[2]);
  const double right = std::min({q00 + 2.0 * q01 + q11, q22 + 2.0 * q02 + q00, q11 + 2.0 * q12 + q22}) / 8.0;
  if (method == ErrorBound::right_triangle) return right;
  // The smallest enclosing circle: the circumcircle of an acute triangle, else the longest edge's.
  const double la = glm::length(b - c), lb = glm::length(c - a), lc = glm::length(a - b);
  const double longest = std::max({la, lb, lc});
  const double l2[3] = {la * la, lb * lb, lc * lc};
  const bool acute = l2[0] + l2[1] > l2[2] && l2[1] + l2[2] > l2[0] && l2[0] + l2[2] > l2[1];
  const double area2 = glm::length(glm::cross(b - a, c - a));  // twice the area
  double R = 0.5 * longest;
  if (acute && area2 > 0.0) R = std::max(R, la * lb * lc / (2.0 * area2));
  const double lambda = direction_bound(M);
  if (method == ErrorBound::circumcircle) {
    // The seed's §3.2.1 bound (Eq. 3.5's circumradius r): d ≤ r for every triangle (Lemmas 1, 2); a degenerate
    // triangle has no circumcircle.
    if (!(area2 > 0.0)) return INFINITY;
    const double r = la * lb * lc / (2.0 * area2);
    return 0.5 * r * r * lambda;
  }
  const double circle = 0.5 * R * R * lambda;
  if (method == ErrorBound::enclosing_circle) return circle;
  return std::min(right, circle);
}

}  // namespace

SecondDerivativeBounds::SecondDerivativeBounds(const TrivariateBSpline<glm::dvec3>& F, std::size_t max_sub_boxes) {
  for (int a = 0; a < 3; ++a) {
    if (F.knots(a).order() < 2) throw std::invalid_argument("deformation-error bounds need order ≥ 2 on every axis");
    periodic_[a] = F.knots(a).is_periodic();
    domain_lo_[a] = F.knots(a).domain_min();
    domain_hi_[a] = F.knots(a).domain_max();
  }
  for (const glm::dvec3& p : F.control_points())
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("the control lattice has a non-finite control point");
  const TrivariateBSpline<glm::dvec3> E = F.periodic_unwrapped().bezier_extracted();
  const glm::ivec3 deg = E.orders() - 1;
  cells_ = E.control_counts() / (deg + 1);
  c0_ = glm::equal(deg, glm::ivec3(1));
  for (int a = 0; a < 3; ++a)
    for (double t : E.knots(a).knots())
      if (breaks_[a].empty() || breaks_[a].back() != t) breaks_[a].push_back(t);
  for (int a = 0; a < 3; ++a)
    for (std::size_t i = 0; i + 1 < breaks_[a].size(); ++i)
      inv_size_[a].push_back(1.0 / (breaks_[a][i + 1] - breaks_[a][i]));
  const std::size_t cells = cell_count();
  // Sub-levels: as many halvings (≤ 4) as the budget of sub-boxes over all levels allows.
  int top = 0;
  for (std::size_t total = cells, per = 1; top < 4; ++top) {
    per *= 8;
    total += cells * per;
    if (total > max_sub_boxes) break;
  }
  levels_.resize(static_cast<std::size_t>(top) + 1);
  level_boxes_.resize(levels_.size());
  for (int l = 0; l <= top; ++l) levels_[l].resize(cells << (3 * l)), level_boxes_[l].resize(cells << (3 * l));
  tbb::parallel_for(std::size_t(0), cells, [&](std::size_t id) {
    const glm::ivec3 c(static_cast<int>(id % cells_.x), static_cast<int>((id / cells_.x) % cells_.y),
                       static_cast<int>(id / (static_cast<std::size_t>(cells_.x) * cells_.y)));
    const glm::ivec3 base = c * (deg + 1);
    Net P(static_cast<std::size_t>(deg.x + 1) * (deg.y + 1) * (deg.z + 1));
    for (int k = 0; k <= deg.z; ++k)
      for (int j = 0; j <= deg.y; ++j)
        for (int i = 0; i <= deg.x; ++i)
          P[net_index(deg, i, j, k)] = E.control_point(base.x + i, base.y + j, base.z + k);
    glm::dvec3 size;
    for (int a = 0; a < 3; ++a) size[a] = breaks_[a][c[a] + 1] - breaks_[a][c[a]];
    // Breadth-first: the nets of level l, sub-box index sx + n (sy + n sz).
    std::vector<Net> nets{std::move(P)};
    for (int l = 0; l <= top; ++l) {
      const int n = 1 << l;
      for (std::size_t s = 0; s < nets.size(); ++s) {
        const BoxBound b = bound_net(nets[s], deg, size / double(n));
        levels_[l][(id << (3 * l)) + s] = b.m;
        level_boxes_[l][(id << (3 * l)) + s] = b.box;
      }
      if (l == top) break;
      std::vector<Net> next(nets.size() * 8);
      for (int sz = 0; sz < n; ++sz)
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx) {
            const auto [x0, x1] = halve(nets[sx + n * (sy + static_cast<std::size_t>(n) * sz)], deg, 0);
            const Net* xs[2] = {&x0, &x1};
            for (int dx = 0; dx < 2; ++dx) {
              const auto [y0, y1] = halve(*xs[dx], deg, 1);
              const Net* ys[2] = {&y0, &y1};
              for (int dy = 0; dy < 2; ++dy) {
                auto [z0, z1] = halve(*ys[dy], deg, 2);
                const int m = 2 * n;
                const std::size_t at = (2 * sx + dx) + m * ((2 * sy + dy) + static_cast<std::size_t>(m) * (2 * sz));
                next[at] = std::move(z0);
                next[at + static_cast<std::size_t>(m) * m] = std::move(z1);
              }
            }
          }
      nets = std::move(next);
    }
  });
}

int SecondDerivativeBounds::cell_index(int a, double x, bool upper) const {
  const auto& b = breaks_[a];
  double shift = 0.0;
  if (periodic_[a]) {
    const double period = domain_hi_[a] - domain_lo_[a];
    shift = std::floor((x - domain_lo_[a]) / period);
    x -= shift * period;
  }
  // lower: a point on a knot plane belongs to the cell below as well (lower_bound); upper: to the cell above.
  const auto it = upper ? std::upper_bound(b.begin(), b.end(), x) : std::lower_bound(b.begin(), b.end(), x);
  int i = static_cast<int>(it - b.begin()) - 1;
  if (!periodic_[a]) return std::clamp(i, 0, cells_[a] - 1);
  return std::clamp(i, -1, cells_[a]) + static_cast<int>(shift) * cells_[a];
}

bool SecondDerivativeBounds::in_domain(const glm::dvec3& lo, const glm::dvec3& hi) const {
  for (int a = 0; a < 3; ++a) {
    if (periodic_[a]) continue;
    const double slack = 1e-9 * (domain_hi_[a] - domain_lo_[a]);
    if (lo[a] < domain_lo_[a] - slack || hi[a] > domain_hi_[a] + slack) return false;
  }
  return true;
}

template <class PerBox>
void SecondDerivativeBounds::for_boxes(const glm::dvec3& lo, const glm::dvec3& hi, PerBox&& fn) const {
  // A box touching a knot plane meets the cells on both sides (second derivatives may jump there); on a periodic axis
  // the cells repeat every period (indices taken modulo the cell count). Within a cell F is one polynomial, so the
  // sub-boxes meeting the box are taken at the finest level where it spans at most two of them per axis.
  glm::ivec3 first, last;
  for (int a = 0; a < 3; ++a) {
    first[a] = cell_index(a, lo[a], false);
    last[a] = std::max(cell_index(a, hi[a], true), first[a]);
    if (last[a] - first[a] >= cells_[a]) first[a] = 0, last[a] = cells_[a] - 1;  // a whole period or more
  }
  const int top = sub_levels();
  glm::ivec3 c;
  for (c.z = first.z; c.z <= last.z; ++c.z)
    for (c.y = first.y; c.y <= last.y; ++c.y)
      for (c.x = first.x; c.x <= last.x; ++c.x) {
        glm::ivec3 w;     // the stored cell
        glm::dvec2 t[3];  // the box in the cell's local [0,1] coordinates
        int level = top;
        for (int a = 0; a < 3; ++a) {
          const int k = c[a] >= 0 ? c[a] / cells_[a] : -((-c[a] + cells_[a] - 1) / cells_[a]);  // floor division
          w[a] = c[a] - k * cells_[a];
          const double shift = periodic_[a] ? k * (domain_hi_[a] - domain_lo_[a]) : 0.0;
          const double c0 = breaks_[a][w[a]] + shift, inv = inv_size_[a][w[a]];
          t[a] = glm::clamp(glm::dvec2(lo[a] - c0, hi[a] - c0) * inv, 0.0, 1.0);
          // The finest level whose sub-boxes are at least as wide as the extent: ⌊−log₂ extent⌋, here from the
          // binary exponent of extent ∈ (0, 1] (−e − 1, one level coarser at exact powers of two: still sound).
          const double extent = t[a].y - t[a].x;
          if (extent > 0.0) {
            const int e = static_cast<int>((std::bit_cast<std::uint64_t>(extent) >> 52) & 0x7ff) - 1023;
            level = std::min(level, std::clamp(-e - 1, 0, top));
          }
        }
        const int n = 1 << level;
        const std::size_t id =
            w.x + static_cast<std::size_t>(cells_.x) * (w.y + static_cast<std::size_t>(cells_.y) * w.z);
        glm::ivec3 s0, s1;
        for (int a = 0; a < 3; ++a) {
          s0[a] = std::min(static_cast<int>(t[a].x * n), n - 1);
          s1[a] = std::min(static_cast<int>(t[a].y * n), n - 1);
        }
        for (int sz = s0.z; sz <= s1.z; ++sz)
          for (int sy = s0.y; sy <= s1.y; ++sy)
            for (int sx = s0.x; sx <= s1.x; ++sx)
              fn(level,
                 (id << (3 * level)) + sx + static_cast<std::size_t>(n) * (sy + static_cast<std::size_t>(n) * sz));
      }
}

glm::dmat3 SecondDerivativeBounds::over_box(const glm::dvec3& lo, const glm::dvec3& hi) const {
  std::array<double, 6> m{};
  for_boxes(lo, hi, [&](int level, std::size_t at) {
    const std::array<double, 6>& b = levels_[level][at];
    for (int e = 0; e < 6; ++e) m[e] = std::max(m[e], b[e]);
  });
  return glm::dmat3(m[0], m[3], m[4], m[3], m[1], m[5], m[4], m[5], m[2]);
}

glm::dmat3 SecondDerivativeBounds::over_box_along(const glm::dvec3& lo, const glm::dvec3& hi,
                                                  const glm::dvec3& n) const {
  const glm::dvec3 an = glm::abs(n);
  std::array<double, 6> m{};
  for_boxes(lo, hi, [&](int level, std::size_t at) {
    const std::array<double, 6>& norms = levels_[level][at];
    const std::array<double, 36>& box = level_boxes_[level][at];
    for (int e = 0; e < 6; ++e) {
      const double* q = &box[6 * e];
      // max over the component box of |d·n|: |centre·n| + Σ|n_i| half_i; never more than the norm bound (|d·n| ≤ ‖d‖
      // for a unit n), which the box's corners can exceed.
      const double k = std::abs(q[0] * n.x + q[1] * n.y + q[2] * n.z) + an.x * q[3] + an.y * q[4] + an.z * q[5];
      m[e] = std::max(m[e], std::min(k, norms[e]));
    }
  });
  return glm::dmat3(m[0], m[3], m[4], m[3], m[1], m[5], m[4], m[5], m[2]);
}

bool SecondDerivativeBounds::crosses_kink(const glm::dvec3& lo, const glm::dvec3& hi) const {
  for (int a = 0; a < 3; ++a) {
    if (!c0_[a]) continue;
    // The cell holding lo (a point on a knot plane counts for the cell above) and the one holding hi (for the cell
    // below): different cells mean a knot plane strictly inside.
    if (cell_index(a, hi[a], false) > cell_index(a, lo[a], true)) return true;
  }
  return false;
}

double triangle_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c, ErrorBound method) {
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  if (!bounds.in_domain(lo, hi) || bounds.crosses_kink(lo, hi)) return INFINITY;
  return bound_from_matrix(bounds.over_box(lo, hi), a, b, c, method);
}

double triangle_normal_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                                   const glm::dvec3& c, const glm::dvec3& n, ErrorBound method) {
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  if (!bounds.in_domain(lo, hi) || bounds.crosses_kink(lo, hi)) return INFINITY;
  return bound_from_matrix(bounds.over_box_along(lo, hi, n), a, b, c, method);
}

std::vector<double> triangle_error_bounds(const SecondDerivativeBounds& bounds, const std::vector<glm::dvec3>& params,
                                          const std::vector<glm::uvec3>& triangles, const glm::dvec3& param_offset,
                                          ErrorBound method) {
  const std::size_t nv = params.size();
  for (const glm::uvec3& t : triangles)
    if (t.x >= nv || t.y >= nv || t.z >= nv) throw std::invalid_argument("triangle_error_bounds: index out of range");
  std::vector<double> out(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t f = r.begin(); f != r.end(); ++f) {
                        const glm::uvec3 t = triangles[f];
                        out[f] = triangle_error_bound(bounds, params[t.x] + param_offset, params[t.y] + param_offset,
                                                      params[t.z] + param_offset, method);
                      }
                    });
  return out;
}

const char* error_bound_name(ErrorBound m) {
  return enum_name(m, {"right_triangle", "circumcircle", "enclosing_circle", "best"});
}

namespace {

// E(s,t) = F(T(s,t)) − T_F(s,t) and its partials in (s,t), each projected by `project` (identity, or onto a normal).
struct ErrorJet {
  glm::dvec3 e, es, et, ess, est, ett;
};

template <class Project>
ErrorJet error_jet(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                   const glm::dvec3& c, const glm::dvec3& fa, const glm::dvec3& fb, const glm::dvec3& fc, double s,
                   double t, Project&& project) {
  const glm::dvec3 e1 = a - c, e2 = b - c;
  const auto d = F.eval_second(c + s * e1 + t * e2);
  ErrorJet j{};
  j.e = d.value - ((1.0 - s - t) * fc + s * fa + t * fb);
  j.es = -(fa - fc), j.et = -(fb - fc);
  for (int x = 0; x < 3; ++x) {
    j.es += e1[x] * d.d[x], j.et += e2[x] * d.d[x];
    for (int y = 0; y < 3; ++y) {
      j.ess += e1[x] * e1[y] * d.dd[x][y];
      j.est += e1[x] * e2[y] * d.dd[x][y];
      j.ett += e2[x] * e2[y] * d.dd[x][y];
    }
  }
  for (glm::dvec3* v : {&j.e, &j.es, &j.et, &j.ess, &j.est, &j.ett}) *v = project(*v);
  return j;
}

// The largest ‖E‖ over the triangle (s, t ≥ 0, s + t ≤ 1) found by the barycentric grid of n steps per edge, two finer
// grids around the worst sample, then Newton's method on ½‖E‖² from there (a stationary point inside, or along the
// edge it reaches). A lower bound of the true maximum, close to it: what the certified bounds are checked against.
template <class Project>
double sampled_max(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                   const glm::dvec3& c, int n, Project&& project) {
  if (n < 1) throw std::invalid_argument("triangle_error_sampled: n must be ≥ 1");
  const glm::dvec3 fa = F.eval(a), fb = F.eval(b), fc = F.eval(c);
  auto error = [&](double s, double t) {
    if (s < 0.0 || t < 0.0 || s + t > 1.0) return -1.0;
    return glm::length(project(F.eval(c + s * (a - c) + t * (b - c)) - ((1.0 - s - t) * fc + s * fa + t * fb)));
  };
  double best = 0.0, bs = 0.0, bt = 0.0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double e = error(double(i) / n, double(j) / n);
      if (e > best) best = e, bs = double(i) / n, bt = double(j) / n;
    }
  double h = 1.0 / n;
  for (int round = 0; round < 2; ++round) {
    const double cs = bs, ct = bt;
    for (int i = -8; i <= 8; ++i)
      for (int j = -8; j <= 8; ++j) {
        const double s = cs + i * h / 8.0, t = ct + j * h / 8.0;
        const double e = error(s, t);
        if (e > best) best = e, bs = s, bt = t;
      }
    h /= 8.0;
  }
  // Newton on φ = ½‖E‖²: ∇φ = (E·E_s, E·E_t), ∇²φ = [E_s·E_s + E·E_ss, …]; steps only where ∇²φ is negative definite
  // (a maximum nearby), shortened to stay in the triangle.
  double s = bs, t = bt;
  for (int it = 0; it < 12; ++it) {
    const ErrorJet j = error_jet(F, a, b, c, fa, fb, fc, s, t, project);
    const double gs = glm::dot(j.e, j.es), gt = glm::dot(j.e, j.et);
    const double hss = glm::dot(j.es, j.es) + glm::dot(j.e, j.ess), hst = glm::dot(j.es, j.et) + glm::dot(j.e, j.est),
                 htt = glm::dot(j.et, j.et) + glm::dot(j.e, j.ett);
    const double det = hss * htt - hst * hst;
    if (!(hss < 0.0 && det > 0.0)) break;
    double ds = -(htt * gs - hst * gt) / det, dt = -(hss * gt - hst * gs) / det;
    double scale = 1.0;  // the largest fraction of the step that stays in the triangle
    if (s + ds < 0.0) scale = std::min(scale, s / -ds);
    if (t + dt < 0.0) scale = std::min(scale, t / -dt);
    if (s + t + ds + dt > 1.0) scale = std::min(scale, (1.0 - s - t) / (ds + dt));
    ds *= scale, dt *= scale;
    s = std::clamp(s + ds, 0.0, 1.0), t = std::clamp(t + dt, 0.0, 1.0 - s);
    const double e = error(s, t);
    if (e > best) best = e;
    if (std::abs(ds) + std::abs(dt) < 1e-13) break;
  }
  return best;
}

}  // namespace

double triangle_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, int n) {
  return sampled_max(F, a, b, c, n, [](const glm::dvec3& v) { return v; });
}

double triangle_normal_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c, const glm::dvec3& normal, int n) {
  return sampled_max(F, a, b, c, n, [&](const glm::dvec3& v) { return glm::dot(v, normal) * normal; });
}

}  // namespace trispline::core
