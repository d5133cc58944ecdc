#include "core/ffd/deformation_bounds.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

}  // namespace

SecondDerivativeBounds::SecondDerivativeBounds(const TrivariateBSpline<glm::dvec3>& F) {
  for (int a = 0; a < 3; ++a) {
    if (F.knots(a).is_periodic())
      throw std::invalid_argument("deformation-error bounds of periodic lattices are not supported");
    if (F.knots(a).order() < 2) throw std::invalid_argument("deformation-error bounds need order ≥ 2 on every axis");
  }
  for (const glm::dvec3& p : F.control_points())
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("the control lattice has a non-finite control point");
  const TrivariateBSpline<glm::dvec3> E = F.bezier_extracted();
  const glm::ivec3 deg = E.orders() - 1;
  cells_ = E.control_counts() / (deg + 1);
  c0_ = glm::equal(deg, glm::ivec3(1));
  for (int a = 0; a < 3; ++a)
    for (double t : E.knots(a).knots())
      if (breaks_[a].empty() || breaks_[a].back() != t) breaks_[a].push_back(t);
  m_.resize(static_cast<std::size_t>(cells_.x) * cells_.y * cells_.z);
  for (int cz = 0; cz < cells_.z; ++cz)
    for (int cy = 0; cy < cells_.y; ++cy)
      for (int cx = 0; cx < cells_.x; ++cx) {
        const glm::ivec3 c(cx, cy, cz), base = c * (deg + 1);
        auto P = [&](int i, int j, int k) -> const glm::dvec3& { return E.control_point(base.x + i, base.y + j, base.z + k); };
        glm::dvec3 size;
        for (int a = 0; a < 3; ++a) size[a] = breaks_[a][c[a] + 1] - breaks_[a][c[a]];
        std::array<double, 6> m{};
        // Pure second partials: p(p−1)/Δ² times the second differences along the axis.
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
                mx = std::max(mx, glm::length(P(q2.x, q2.y, q2.z) - 2.0 * P(q1.x, q1.y, q1.z) + P(q.x, q.y, q.z)));
              }
          m[a] = deg[a] * (deg[a] - 1) * mx / (size[a] * size[a]);
        }
        // Mixed partials: p·q/(Δa·Δb) times the mixed differences.
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
                mx = std::max(mx, glm::length(P(qab.x, qab.y, qab.z) - P(qa.x, qa.y, qa.z) - P(qb.x, qb.y, qb.z) +
                                              P(q.x, q.y, q.z)));
              }
          m[3 + e] = deg[a] * deg[b] * mx / (size[a] * size[b]);
        }
        m_[cx + static_cast<std::size_t>(cells_.x) * (cy + static_cast<std::size_t>(cells_.y) * cz)] = m;
      }
}

glm::dmat3 SecondDerivativeBounds::over_box(const glm::dvec3& lo, const glm::dvec3& hi) const {
  glm::ivec3 first, last;
  for (int a = 0; a < 3; ++a) {
    const auto& b = breaks_[a];
    // A box touching a knot plane meets the cells on both sides (second derivatives may jump there).
    first[a] = std::clamp(static_cast<int>(std::lower_bound(b.begin(), b.end(), lo[a]) - b.begin()) - 1, 0, cells_[a] - 1);
    last[a] = std::clamp(static_cast<int>(std::upper_bound(b.begin(), b.end(), hi[a]) - b.begin()) - 1, 0, cells_[a] - 1);
    last[a] = std::max(last[a], first[a]);
  }
  std::array<double, 6> m{};
  for (int cz = first.z; cz <= last.z; ++cz)
    for (int cy = first.y; cy <= last.y; ++cy)
      for (int cx = first.x; cx <= last.x; ++cx) {
        const auto& c = m_[cx + static_cast<std::size_t>(cells_.x) * (cy + static_cast<std::size_t>(cells_.y) * cz)];
        for (int e = 0; e < 6; ++e) m[e] = std::max(m[e], c[e]);
      }
  return glm::dmat3(m[0], m[3], m[4], m[3], m[1], m[5], m[4], m[5], m[2]);
}

bool SecondDerivativeBounds::crosses_kink(const glm::dvec3& lo, const glm::dvec3& hi) const {
  for (int a = 0; a < 3; ++a) {
    if (!c0_[a]) continue;
    const auto& b = breaks_[a];
    // The cell holding lo (a point on a knot plane counts for the cell above) and the one holding hi (for the cell
    // below): different cells mean a knot plane strictly inside.
    const auto first = std::upper_bound(b.begin(), b.end(), lo[a]) - b.begin();
    const auto last = std::lower_bound(b.begin(), b.end(), hi[a]) - b.begin();
    if (last > first) return true;
  }
  return false;
}

double triangle_error_bound(const SecondDerivativeBounds& bounds, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c, ErrorBound method) {
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  if (bounds.crosses_kink(lo, hi)) return INFINITY;
  const glm::dmat3 M = bounds.over_box(lo, hi);
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
  const double circle = 0.5 * R * R * direction_bound(M);
  if (method == ErrorBound::enclosing_circle) return circle;
  return std::min(right, circle);
}

double triangle_error_sampled(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, int n) {
  const glm::dvec3 fa = F.eval(a), fb = F.eval(b), fc = F.eval(c);
  auto error = [&](double s, double t) {
    if (s < 0.0 || t < 0.0 || s + t > 1.0) return -1.0;
    return glm::length(F.eval(c + s * (a - c) + t * (b - c)) - ((1.0 - s - t) * fc + s * fa + t * fb));
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
  return best;
}

}  // namespace trispline::core
