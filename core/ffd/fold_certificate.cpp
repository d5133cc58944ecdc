#include "core/ffd/fold_certificate.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/base/enum_names.h"

namespace trispline::core {

namespace {

// A trivariate Bernstein polynomial (scalar or vector coefficients) of degree (n[0], n[1], n[2]) on [0,1]³;
// coefficient (i, j, k) at c[i + (n0+1)·(j + (n1+1)·k)].
template <class T>
struct Bernstein {
  glm::ivec3 n{0};
  std::vector<T> c;
  Bernstein() = default;
  explicit Bernstein(const glm::ivec3& degree)
      : n(degree), c(static_cast<std::size_t>(degree.x + 1) * (degree.y + 1) * (degree.z + 1)) {}
  std::size_t at(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           (n.x + 1) * (static_cast<std::size_t>(j) + (n.y + 1) * static_cast<std::size_t>(k));
  }
};

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// Coefficients times C(n0,i)·C(n1,j)·C(n2,k) (scale = +1) or divided by them (scale = −1): products of Bernstein forms
// are plain convolutions of the scaled coefficients.
template <class T>
void rescale(Bernstein<T>& b, int scale) {
  std::vector<double> w[3];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= b.n[a]; ++i) w[a].push_back(binomial(b.n[a], i));
  for (int k = 0; k <= b.n.z; ++k)
    for (int j = 0; j <= b.n.y; ++j)
      for (int i = 0; i <= b.n.x; ++i) {
        const double f = w[0][i] * w[1][j] * w[2][k];
        b.c[b.at(i, j, k)] = scale > 0 ? b.c[b.at(i, j, k)] * f : b.c[b.at(i, j, k)] / f;
      }
}

// Scaled product: out = a ⊛ b with op(x, y) accumulated (cross or dot).
template <class R, class A, class B, class Op>
Bernstein<R> convolve(const Bernstein<A>& a, const Bernstein<B>& b, Op op) {
  Bernstein<R> out(a.n + b.n);
  for (int k1 = 0; k1 <= a.n.z; ++k1)
    for (int j1 = 0; j1 <= a.n.y; ++j1)
      for (int i1 = 0; i1 <= a.n.x; ++i1) {
        const A& x = a.c[a.at(i1, j1, k1)];
        for (int k2 = 0; k2 <= b.n.z; ++k2)
          for (int j2 = 0; j2 <= b.n.y; ++j2)
            for (int i2 = 0; i2 <= b.n.x; ++i2)
              out.c[out.at(i1 + i2, j1 + j2, k1 + k2)] += op(x, b.c[b.at(i2, j2, k2)]);
      }
  return out;
}

// det J of one Bézier cell (control points P, (p+1)(q+1)(r+1), u fastest) in its local coordinates [0,1]³.
Bernstein<double> det_jacobian(const std::vector<glm::dvec3>& P, const glm::ivec3& deg) {
  const Bernstein<glm::dvec3> cell{deg};
  Bernstein<glm::dvec3> d[3];
  for (int a = 0; a < 3; ++a) {
    glm::ivec3 n = deg;
    n[a] -= 1;
    d[a] = Bernstein<glm::dvec3>(n);
    for (int k = 0; k <= n.z; ++k)
      for (int j = 0; j <= n.y; ++j)
        for (int i = 0; i <= n.x; ++i) {
          glm::ivec3 hi(i, j, k);
          hi[a] += 1;
          d[a].c[d[a].at(i, j, k)] = double(deg[a]) * (P[cell.at(hi.x, hi.y, hi.z)] - P[cell.at(i, j, k)]);
        }
    rescale(d[a], +1);
  }
  const Bernstein<glm::dvec3> vw =
      convolve<glm::dvec3>(d[1], d[2], [](const glm::dvec3& x, const glm::dvec3& y) { return glm::cross(x, y); });
  Bernstein<double> det =
      convolve<double>(d[0], vw, [](const glm::dvec3& x, const glm::dvec3& y) { return glm::dot(x, y); });
  rescale(det, -1);
  return det;
}

// de Casteljau halves of b along `axis`.
void split(const Bernstein<double>& b, int axis, Bernstein<double>& lo, Bernstein<double>& hi) {
  lo = b, hi = b;
  const int n = b.n[axis];
  glm::ivec3 m = b.n + 1;
  m[axis] = 1;
  std::vector<double> w(n + 1);
  for (int k = 0; k < m.z; ++k)
    for (int j = 0; j < m.y; ++j)
      for (int i = 0; i < m.x; ++i) {
        auto idx = [&](int t) {
          glm::ivec3 q(i, j, k);
          q[axis] = t;
          return b.at(q.x, q.y, q.z);
        };
        for (int t = 0; t <= n; ++t) w[t] = b.c[idx(t)];
        // Row r of the triangle: lo gets its first entry, hi its last.
        for (int r = 0; r <= n; ++r) {
          lo.c[idx(r)] = w[0];
          hi.c[idx(n - r)] = w[n - r];
          for (int t = 0; t < n - r; ++t) w[t] = 0.5 * (w[t] + w[t + 1]);
        }
      }
}

// b at a local point x ∈ [0,1]³ (de Casteljau along each axis).
double value_at(const Bernstein<double>& b, const glm::dvec3& x) {
  std::vector<double> c = b.c;
  glm::ivec3 n = b.n;
  // Reduce u, then v, then w: each pass collapses one axis to a single coefficient.
  for (int axis = 0; axis < 3; ++axis) {
    const glm::ivec3 m = n + 1;
    glm::ivec3 r = m;
    r[axis] = 1;
    std::vector<double> out(static_cast<std::size_t>(r.x) * r.y * r.z);
    std::vector<double> w(n[axis] + 1);
    for (int k = 0; k < r.z; ++k)
      for (int j = 0; j < r.y; ++j)
        for (int i = 0; i < r.x; ++i) {
          for (int t = 0; t <= n[axis]; ++t) {
            glm::ivec3 q(i, j, k);
            q[axis] = t;
            w[t] = c[q.x + static_cast<std::size_t>(m.x) * (q.y + static_cast<std::size_t>(m.y) * q.z)];
          }
          for (int level = n[axis]; level > 0; --level)
            for (int t = 0; t < level; ++t) w[t] = (1.0 - x[axis]) * w[t] + x[axis] * w[t + 1];
          out[i + static_cast<std::size_t>(r.x) * (j + static_cast<std::size_t>(r.y) * k)] = w[0];
        }
    c = std::move(out);
    n[axis] = 0;
  }
  return c[0];
}

// The quick sufficient test: by the convex hull property each column ∂F/∂a of J lies, everywhere in the cell, in the
// component box of its derivative's Bézier control points. Preconditioned by M = J̄⁻¹ (J̄ from the boxes' centres,
// det J̄ > 0), if every matrix A = M·J with such columns is strictly column-diagonally dominant with a positive
// diagonal, Gershgorin puts all of A's eigenvalues in the right half-plane, so det A > 0 and det J = det A · det J̄ > 0
// on the whole cell. It needs only the first differences (48 for a tri-cubic cell, not 729 products) and decides the
// gently deformed cells of a lattice; what it cannot decide goes to the exact Bernstein test. Like Choi & Lee's
// displacement bound for uniform cubic lattices, but for any order, knot vector and affine pose of the lattice.
bool quick_fold_free(const std::vector<glm::dvec3>& P, const glm::ivec3& deg) {
  const Bernstein<glm::dvec3> cell{deg};
  glm::dvec3 lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    glm::ivec3 n = deg;
    n[a] -= 1;
    bool first = true;
    for (int k = 0; k <= n.z; ++k)
      for (int j = 0; j <= n.y; ++j)
        for (int i = 0; i <= n.x; ++i) {
          glm::ivec3 up(i, j, k);
          up[a] += 1;
          const glm::dvec3 d = P[cell.at(up.x, up.y, up.z)] - P[cell.at(i, j, k)];  // ∝ ∂F/∂a (positive factor)
          lo[a] = first ? d : glm::min(lo[a], d);
          hi[a] = first ? d : glm::max(hi[a], d);
          first = false;
        }
  }
  glm::dmat3 centre;  // columns: box centres
  for (int a = 0; a < 3; ++a) centre[a] = 0.5 * (lo[a] + hi[a]);
  const double det_centre = glm::determinant(centre);
  if (!(det_centre > 0.0)) return false;
  const glm::dmat3 M = glm::inverse(centre);
  glm::dmat3 absM;
  for (int c = 0; c < 3; ++c) absM[c] = glm::abs(M[c]);
  for (int a = 0; a < 3; ++a) {
    const glm::dvec3 mid = M * centre[a];                   // ≈ e_a
    const glm::dvec3 rad = absM * (0.5 * (hi[a] - lo[a]));  // interval radius of column a of M·J
    // Outward slack for rounding in M and the products.
    const double slack = 1e-12 * (glm::length(mid) + glm::length(rad) + 1.0);
    double off = 0.0;
    for (int b = 0; b < 3; ++b)
      if (b != a) off += std::abs(mid[b]) + rad[b];
    if (!(mid[a] - rad[a] - slack > off + slack)) return false;
  }
  return true;
}

struct CellVerdict {
  bool quick = false;  // decided by quick_fold_free
  FoldVerdict verdict = FoldVerdict::fold_free;
  glm::dvec3 local{0.0};  // fold: the local point with det J ≤ 0
  double det = 0.0;
  double min_coefficient = 0.0;
  std::size_t boxes = 0;
  std::size_t max_boxes = 0;  // this cell's share of FoldCertificateOptions::max_boxes
  bool budget = false;        // the share ran out
};

// Judges the box [lo, lo + size]³ (local coordinates) whose det J is b.
FoldVerdict judge(const Bernstein<double>& b, const glm::dvec3& lo, double size, int depth, int max_depth,
                  CellVerdict& out) {
  if (out.boxes >= out.max_boxes) {
    out.budget = true;
    return FoldVerdict::undecided;
  }
  ++out.boxes;
  const double mn = *std::min_element(b.c.begin(), b.c.end());
  if (mn > 0.0) return FoldVerdict::fold_free;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 q(corner & 1 ? b.n.x : 0, corner & 2 ? b.n.y : 0, corner & 4 ? b.n.z : 0);
    const double v = b.c[b.at(q.x, q.y, q.z)];
    if (v <= 0.0) {
      // Reported a little inside the box when det J is ≤ 0 there too: a corner on a knot plane belongs to the
      // neighbouring cell as well, where F's derivatives (order 2: discontinuous) may differ.
      const glm::dvec3 corner_local(corner & 1 ? 1 : 0, corner & 2 ? 1 : 0, corner & 4 ? 1 : 0);
      const glm::dvec3 inside = glm::mix(corner_local, glm::dvec3(0.5), 1e-3);
      const double vi = value_at(b, inside);
      out.local = lo + size * (vi <= 0.0 ? inside : corner_local);
      out.det = vi <= 0.0 ? vi : v;
      return FoldVerdict::fold;
    }
  }
  if (depth >= max_depth) return FoldVerdict::undecided;
  // Eight children, judged in a fixed order; a fold anywhere decides.
  Bernstein<double> x[2], y[2], z[2];
  split(b, 0, x[0], x[1]);
  FoldVerdict worst = FoldVerdict::fold_free;
  for (int a = 0; a < 2; ++a) {
    split(x[a], 1, y[0], y[1]);
    for (int c = 0; c < 2; ++c) {
      Bernstein<double> z0, z1;
      split(y[c], 2, z0, z1);
      const Bernstein<double>* zs[2] = {&z0, &z1};
      for (int e = 0; e < 2; ++e) {
        const glm::dvec3 child_lo = lo + 0.5 * size * glm::dvec3(a, c, e);
        const FoldVerdict v = judge(*zs[e], child_lo, 0.5 * size, depth + 1, max_depth, out);
        if (v == FoldVerdict::fold) return v;
        if (v == FoldVerdict::undecided) worst = v;
      }
    }
  }
  return worst;
}

}  // namespace

const char* fold_verdict_name(FoldVerdict v) { return enum_name(v, {"fold_free", "fold", "undecided"}, "undecided"); }

FoldCertificate certify_fold_free(const TrivariateBSpline<glm::dvec3>& F, const FoldCertificateOptions& options) {
  if (options.max_depth < 0 || options.max_depth > 12)
    throw std::invalid_argument("max_depth must be 0…12 halvings, got " + std::to_string(options.max_depth));
  if (options.max_boxes == 0) throw std::invalid_argument("max_boxes must be at least 1");
  for (int a = 0; a < 3; ++a)
    if (F.knots(a).order() < 2)
      throw std::invalid_argument(
          "a fold-free certificate needs order ≥ 2 on every axis (a constant axis has det J = 0)");
  for (const glm::dvec3& p : F.control_points())
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("the control lattice has a non-finite control point");
  const TrivariateBSpline<glm::dvec3> E = F.periodic_unwrapped().bezier_extracted();
  const glm::ivec3 deg = E.orders() - 1;
  const glm::ivec3 counts = E.control_counts();
  const glm::ivec3 cells = counts / (deg + 1);
  // The cells' parameter ranges: the distinct knots of each axis.
  std::array<std::vector<double>, 3> breaks;
  for (int a = 0; a < 3; ++a)
    for (double t : E.knots(a).knots())
      if (breaks[a].empty() || breaks[a].back() != t) breaks[a].push_back(t);
  const std::size_t count = static_cast<std::size_t>(cells.x) * cells.y * cells.z;
  std::vector<CellVerdict> verdicts(count);
  // Pass 1: each cell's quick test and its whole-cell box (a share of 1). Pass 2: the cells still mixed share what
  // is left of max_boxes evenly, so a big lattice with a few hard cells gives them the budget (both passes decide
  // from the cell alone: the same verdicts for any thread count).
  const auto judge_cells = [&](const std::vector<std::size_t>& which, bool first) {
    tbb::parallel_for(std::size_t(0), which.size(), [&](std::size_t n) {
      const std::size_t cell = which[n];
      const glm::ivec3 c(static_cast<int>(cell % cells.x), static_cast<int>((cell / cells.x) % cells.y),
                         static_cast<int>(cell / (static_cast<std::size_t>(cells.x) * cells.y)));
      std::vector<glm::dvec3> P;
      P.reserve(static_cast<std::size_t>(deg.x + 1) * (deg.y + 1) * (deg.z + 1));
      for (int k = 0; k <= deg.z; ++k)
        for (int j = 0; j <= deg.y; ++j)
          for (int i = 0; i <= deg.x; ++i)
            P.push_back(E.control_point(c.x * (deg.x + 1) + i, c.y * (deg.y + 1) + j, c.z * (deg.z + 1) + k));
      CellVerdict& v = verdicts[cell];
      if (first && options.quick_test && quick_fold_free(P, deg)) {
        v.quick = true;
        v.min_coefficient = INFINITY;
        v.boxes = 0;
        return;
      }
      const Bernstein<double> det = det_jacobian(P, deg);
      v.min_coefficient = *std::min_element(det.c.begin(), det.c.end());
      v.boxes = 0;
      v.budget = false;
      v.verdict = judge(det, glm::dvec3(0.0), 1.0, 0, options.max_depth, v);
    });
  };
  std::vector<std::size_t> all(count);
  for (std::size_t cell = 0; cell < count; ++cell) all[cell] = cell, verdicts[cell].max_boxes = 1;
  judge_cells(all, true);
  std::vector<std::size_t> mixed;
  std::size_t used = 0;
  for (std::size_t cell = 0; cell < count; ++cell) {
    if (verdicts[cell].budget)
      mixed.push_back(cell);
    else
      used += verdicts[cell].boxes;
  }
  if (!mixed.empty()) {
    const std::size_t left = options.max_boxes > used ? options.max_boxes - used : 0;
    const std::size_t share = std::max<std::size_t>(left / mixed.size(), 1);
    for (std::size_t cell : mixed) verdicts[cell].max_boxes = share;
    judge_cells(mixed, false);
  }
  FoldCertificate out;
  out.cells = count;
  out.min_det_coefficient = INFINITY;
  bool undecided = false;
  for (std::size_t cell = 0; cell < count; ++cell) {
    const CellVerdict& v = verdicts[cell];
    out.boxes += v.boxes;
    out.quick_cells += v.quick ? 1 : 0;
    out.min_det_coefficient = std::min(out.min_det_coefficient, v.min_coefficient);
    const glm::ivec3 c(static_cast<int>(cell % cells.x), static_cast<int>((cell / cells.x) % cells.y),
                       static_cast<int>(cell / (static_cast<std::size_t>(cells.x) * cells.y)));
    if (v.verdict == FoldVerdict::undecided) {
      undecided = true;
      out.budget_cells += v.budget ? 1 : 0;
      out.undecided_cells.push_back(c);
    } else if (v.verdict == FoldVerdict::fold) {
      glm::dvec3 t, scale;
      for (int a = 0; a < 3; ++a) {
        const double t0 = breaks[a][c[a]], t1 = breaks[a][c[a] + 1];
        t[a] = t0 + (t1 - t0) * v.local[a];
        scale[a] = t1 - t0;
      }
      out.fold_cells.push_back(c);
      out.fold_params.push_back(t);
      out.fold_points.push_back(E.eval(t));
      // Local det J per unit of the parameters: divided by the cell's side lengths.
      out.fold_det.push_back(v.det / (scale.x * scale.y * scale.z));
    }
  }
  if (!std::isfinite(out.min_det_coefficient)) out.min_det_coefficient = 0.0;  // no cell needed the Bernstein test
  out.verdict = !out.fold_cells.empty() ? FoldVerdict::fold
                : undecided             ? FoldVerdict::undecided
                                        : FoldVerdict::fold_free;
  return out;
}

}  // namespace trispline::core
