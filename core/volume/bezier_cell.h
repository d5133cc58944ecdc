// Internal helpers on one cell's trivariate Bézier form (order K ≤ 4 per axis, K³ coefficients, first axis fastest),
// written as K×K matrices applied along one axis at a time, with K a compile-time constant so the loops unroll:
//   restriction to a sub-box (de Casteljau subdivision as a matrix, Piegl & Tiller §5.2 / Farin §5.4),
//   the gradient's vector coefficients (the convex hull that bounds ∇D, seed §7.3.2).
#pragma once

#include <array>

namespace trispline::core::bezier_cell {

template <int K>
using Matrix = std::array<std::array<double, K>, K>;

// out = M applied along AXIS (0 = first, fastest): out[..a..] = Σ_r M[a][r]·in[..r..]. in ≠ out.
template <int K, int AXIS>
inline void apply_axis(const Matrix<K>& m, const double* in, double* out) {
  constexpr int stride = AXIS == 0 ? 1 : AXIS == 1 ? K : K * K;
  for (int l = 0; l < K * K; ++l) {
    // Base index of line l: the two other axes' indices.
    const int hi = l / K, lo = l % K;
    const int base = AXIS == 0 ? K * l : AXIS == 1 ? lo + K * K * hi : l;
    double v[K];
    for (int r = 0; r < K; ++r) v[r] = in[base + r * stride];
    for (int a = 0; a < K; ++a) {
      double s = 0.0;
      for (int r = 0; r < K; ++r) s += m[a][r] * v[r];
      out[base + a * stride] = s;
    }
  }
}

template <int K>
inline void apply(const Matrix<K>& m, const double* in, double* out, int axis) {
  if (axis == 0)
    apply_axis<K, 0>(m, in, out);
  else if (axis == 1)
    apply_axis<K, 1>(m, in, out);
  else
    apply_axis<K, 2>(m, in, out);
}

// The same matrix along all three axes (tensor product): in → out (in may be overwritten).
template <int K>
inline void apply3(const Matrix<K>& mx, const Matrix<K>& my, const Matrix<K>& mz, double* in, double* out) {
  double tmp[K * K * K];
  apply_axis<K, 0>(mx, in, tmp);
  apply_axis<K, 1>(my, tmp, in);
  apply_axis<K, 2>(mz, in, out);
}

// Matrix restricting a Bernstein polynomial of order K on [0,1] to [t0, t1]: row a of the result = coefficient a of the
// restricted polynomial (blossom values b(t0^{K−1−a}, t1^a), computed by de Casteljau on unit vectors).
template <int K>
inline Matrix<K> restriction(double t0, double t1) {
  Matrix<K> m{};
  for (int r = 0; r < K; ++r) {
    // Polynomial with coefficient 1 at r: blossom evaluations.
    for (int a = 0; a < K; ++a) {
      double w[K];
      for (int i = 0; i < K; ++i) w[i] = i == r ? 1.0 : 0.0;
      int level = 0;
      for (int step = 0; step < K - 1; ++step, ++level) {
        const double t = step < K - 1 - a ? t0 : t1;
        for (int i = 0; i < K - 1 - level; ++i) w[i] = (1.0 - t) * w[i] + t * w[i + 1];
      }
      m[a][r] = w[0];
    }
  }
  return m;
}

// The gradient's vector coefficients along one axis: the derivative's coefficients p·Δb (degree p − 1) raised back to
// degree p = K − 1: e_a = a·(b_a − b_{a−1}) + (p − a)·(b_{a+1} − b_a). Every gradient of the cell (per unit of its
// local coordinates) is a convex combination of the vectors (e_x, e_y, e_z) at the K³ Bernstein positions.
template <int K>
inline Matrix<K> raised_derivative() {
  Matrix<K> m{};
  const int p = K - 1;
  for (int a = 0; a < K; ++a) {
    if (a > 0) m[a][a - 1] -= a, m[a][a] += a;
    if (a < p) m[a][a + 1] += p - a, m[a][a] -= p - a;
  }
  return m;
}

template <int K>
inline Matrix<K> identity() {
  Matrix<K> m{};
  for (int a = 0; a < K; ++a) m[a][a] = 1.0;
  return m;
}

// g[axis][m] for the K³ coefficients b. The raised-derivative matrix is tridiagonal, so each output needs the two
// differences beside it: e_a = a·Δ_{a−1} + (p − a)·Δ_a with Δ_m = b_{m+1} − b_m.
template <int K>
inline void gradient_vectors(const double* b, double g[3][64]) {
  constexpr int p = K - 1;
  for (int axis = 0; axis < 3; ++axis) {
    const int stride = axis == 0 ? 1 : axis == 1 ? K : K * K;
    double* out = g[axis];
    for (int l = 0; l < K * K; ++l) {
      const int hi = l / K, lo = l % K;
      const int base = axis == 0 ? K * l : axis == 1 ? lo + K * K * hi : l;
      double d[K - 1];
      for (int m = 0; m < p; ++m) d[m] = b[base + (m + 1) * stride] - b[base + m * stride];
      for (int a = 0; a < K; ++a)
        out[base + a * stride] = (a > 0 ? a * d[a - 1] : 0.0) + (a < p ? (p - a) * d[a] : 0.0);
    }
  }
}

}  // namespace trispline::core::bezier_cell
