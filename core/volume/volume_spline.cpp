#include "core/volume/volume_spline.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/volume/bezier_cell.h"

namespace trispline::core {

namespace {

// Power-basis coefficients (x^0 … x^{k−1}) of the k centred uniform B-spline segment polynomials of order k, in
// control order: kPower[k][r][j]. Source: the uniform B-spline basis matrices (e.g. Piegl & Tiller §2.5 with uniform
// knots; order 4 is the cubic B-spline matrix (1/6)[1 4 1 0; −3 0 3 0; 3 −6 3 0; −1 3 −3 1]ᵀ).
constexpr double kPower[5][4][4] = {
    {},
    {},
    {{1.0, -1.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}},
    {{0.5, -1.0, 0.5, 0.0}, {0.5, 1.0, -1.0, 0.0}, {0.0, 0.0, 0.5, 0.0}},
    {{1.0 / 6, -0.5, 0.5, -1.0 / 6}, {2.0 / 3, 0.0, -1.0, 0.5}, {1.0 / 6, 0.5, 0.5, -0.5}, {0.0, 0.0, 0.0, 1.0 / 6}},
};

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Values of the centred cardinal B-spline of order k at the integers 0 and ±1 (the interpolation matrix's diagonal
// and off-diagonal).
void cardinal_at_integers(int order, double& b0, double& b1) {
  switch (order) {
    case 2:
      b0 = 1.0, b1 = 0.0;
      break;
    case 3:
      b0 = 0.75, b1 = 0.125;
      break;
    default:
      b0 = 2.0 / 3.0, b1 = 1.0 / 6.0;
      break;
  }
}

// Solves the interpolation system along one line of n samples in place (stride `stride`): Σ_i c_i B(j − i) = v_j with
// clamped boundary coefficients (c_{−1} = c_0, c_n = c_{n−1}): tridiagonal, diagonally dominant, Thomas algorithm.
void prefilter_line(float* data, std::size_t stride, int n, double b0, double b1, std::vector<double>& cp,
                    std::vector<double>& dp) {
  cp.resize(n), dp.resize(n);
  auto diag = [&](int j) { return (j == 0 || j == n - 1) ? b0 + b1 : b0; };
  double denom = diag(0);
  cp[0] = b1 / denom;
  dp[0] = data[0] / denom;
  for (int j = 1; j < n; ++j) {
    denom = diag(j) - b1 * cp[j - 1];
    cp[j] = b1 / denom;
    dp[j] = (data[j * stride] - b1 * dp[j - 1]) / denom;
  }
  double c = dp[n - 1];
  data[(n - 1) * stride] = static_cast<float>(c);
  for (int j = n - 2; j >= 0; --j) {
    c = dp[j] - cp[j] * c;
    data[j * stride] = static_cast<float>(c);
  }
}

}  // namespace

namespace {

// Closed forms of the cubic (order 4) segment weights and their derivatives (the rows of kPower[4]).
inline void cubic_weights(double x, double* w, double* dw, double* d2w) {
  const double x2 = x * x, x3 = x2 * x, u = 1.0 - x;
  w[0] = u * u * u / 6.0;
  w[1] = (3.0 * x3 - 6.0 * x2 + 4.0) / 6.0;
  w[2] = (-3.0 * x3 + 3.0 * x2 + 3.0 * x + 1.0) / 6.0;
  w[3] = x3 / 6.0;
  if (dw) {
    dw[0] = -0.5 * u * u;
    dw[1] = 1.5 * x2 - 2.0 * x;
    dw[2] = -1.5 * x2 + x + 0.5;
    dw[3] = 0.5 * x2;
  }
  if (d2w) {
    d2w[0] = u;
    d2w[1] = 3.0 * x - 2.0;
    d2w[2] = -3.0 * x + 1.0;
    d2w[3] = x;
  }
}

}  // namespace

void uniform_bspline_weights(int order, double x, double* w, double* dw, double* d2w) {
  if (order == 4) return cubic_weights(x, w, dw, d2w);
  for (int r = 0; r < order; ++r) {
    const double* c = kPower[order][r];
    double v = 0.0, d = 0.0, dd = 0.0;
    for (int j = order - 1; j >= 0; --j) v = v * x + c[j];
    for (int j = order - 1; j >= 1; --j) d = d * x + j * c[j];
    for (int j = order - 1; j >= 2; --j) dd = dd * x + j * (j - 1) * c[j];
    w[r] = v;
    if (dw) dw[r] = d;
    if (d2w) d2w[r] = dd;
  }
}

VolumeSpline::VolumeSpline(const ScalarVolume& volume, int order, bool interpolate)
    : order_(order), interpolate_(interpolate), dims_(volume.dims) {
  if (order < 2 || order > 4)
    throw std::invalid_argument("volume spline order must be 2, 3 or 4 (degree + 1), got " + std::to_string(order));
  if (const std::string e = scalar_volume_error(volume); !e.empty()) throw std::invalid_argument(e);
  shift_ = (order % 2 == 0) ? 0.0 : -0.5;
  for (int a = 0; a < 3; ++a) span_count_[a] = (order % 2 == 0) ? dims_[a] - 1 : dims_[a];
  control_ = volume.values;
  if (interpolate && order > 2) {
    double b0 = 0, b1 = 0;
    cardinal_at_integers(order, b0, b1);
    std::vector<double> cp, dp;
    const std::size_t nx = dims_[0], ny = dims_[1], nz = dims_[2];
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t j = 0; j < ny; ++j) prefilter_line(&control_[nx * (j + ny * k)], 1, dims_[0], b0, b1, cp, dp);
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t i = 0; i < nx; ++i) prefilter_line(&control_[i + nx * ny * k], nx, dims_[1], b0, b1, cp, dp);
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) prefilter_line(&control_[i + nx * j], nx * ny, dims_[2], b0, b1, cp, dp);
    for (float v : control_)
      if (!std::isfinite(v)) throw std::invalid_argument("the interpolating spline's coefficients are not finite");
  }
  const auto [lo, hi] = std::minmax_element(control_.begin(), control_.end());
  control_min_ = *lo, control_max_ = *hi;
  index_to_world_ = volume.index_to_world;
  world_to_index_ = glm::inverse(index_to_world_);
  gradient_to_world_ = glm::transpose(glm::dmat3(world_to_index_));
  // Bézier extraction of one span: Bernstein coefficient a of segment polynomial r.
  const int p = order - 1;
  for (int r = 0; r < order; ++r)
    for (int a = 0; a < order; ++a) {
      double b = 0.0;
      for (int j = 0; j <= a; ++j) b += binomial(a, j) / binomial(p, j) * kPower[order][r][j];
      to_bezier_[a * order + r] = b;
    }
}

float VolumeSpline::control(int i, int j, int l) const {
  i = std::clamp(i, 0, dims_[0] - 1), j = std::clamp(j, 0, dims_[1] - 1), l = std::clamp(l, 0, dims_[2] - 1);
  return control_[static_cast<std::size_t>(i) +
                  static_cast<std::size_t>(dims_[0]) *
                      (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_[1]) * l)];
}

int VolumeSpline::span_of(int axis, double t) const {
  const double s = std::floor(t - shift_);
  if (!(s > 0.0)) return 0;  // NaN too
  return static_cast<int>(std::min<double>(s, span_count_[axis] - 1));
}

namespace {

template <int K>
struct AxisBasis {
  int idx[K];
  double w[K], dw[K], d2w[K];
};

template <int K>
inline void axis_basis(const VolumeSpline& s, int axis, double t, bool derivatives, AxisBasis<K>& b) {
  const int n = s.dims()[axis];
  t = std::clamp(t, 0.0, double(n - 1));
  const int span = s.span_of(axis, t);
  const int first = s.first_control(span);
  if constexpr (K == 4)
    cubic_weights(t - s.span_begin(span), b.w, derivatives ? b.dw : nullptr, derivatives ? b.d2w : nullptr);
  else
    uniform_bspline_weights(K, t - s.span_begin(span), b.w, derivatives ? b.dw : nullptr,
                            derivatives ? b.d2w : nullptr);
  if (first >= 0 && first + K <= n) {
    for (int r = 0; r < K; ++r) b.idx[r] = first + r;
  } else {
    for (int r = 0; r < K; ++r) b.idx[r] = std::clamp(first + r, 0, n - 1);
  }
}

// The three axes' bases at x and the control-point strides: where every tensor contraction starts.
template <int K>
struct TensorBasis {
  TensorBasis(const VolumeSpline& s, const glm::dvec3& p, bool derivatives)
      : nx(s.dims()[0]), nxy(nx * s.dims()[1]), cp(s.control_points().data()) {
    axis_basis<K>(s, 0, p.x, derivatives, x);
    axis_basis<K>(s, 1, p.y, derivatives, y);
    axis_basis<K>(s, 2, p.z, derivatives, z);
  }
  // The x-row of control points used at y index b and z index c (indices into the axes' bases).
  const float* row(int b, int c) const { return cp + z.idx[c] * nxy + y.idx[b] * nx; }
  AxisBasis<K> x, y, z;
  std::size_t nx, nxy;
  const float* cp;
};

VolumeJet make_jet(double v, double dx, double dy, double dz, double dxx, double dyy, double dzz, double dxy,
                   double dxz, double dyz) {
  VolumeJet j;
  j.value = v;
  j.gradient = {dx, dy, dz};
  j.hessian = glm::dmat3(dxx, dxy, dxz, dxy, dyy, dyz, dxz, dyz, dzz);
  return j;
}

// D at x with the order K a compile-time constant (the loops unroll).
template <int K>
double value_k(const VolumeSpline& s, const glm::dvec3& x) {
  const TensorBasis<K> t(s, x, false);
  const AxisBasis<K>&bx = t.x, &by = t.y, &bz = t.z;
  double sum = 0.0;
  for (int c = 0; c < K; ++c) {
    double sy = 0.0;
    for (int b = 0; b < K; ++b) {
      const float* row = t.row(b, c);
      double sx = 0.0;
      for (int a = 0; a < K; ++a) sx += bx.w[a] * row[bx.idx[a]];
      sy += by.w[b] * sx;
    }
    sum += bz.w[c] * sy;
  }
  return sum;
}

// D, ∇D and the Hessian at x: contract x first (value, d, d²), then y (six combinations), then z (ten results).
template <int K>
VolumeJet jet_k(const VolumeSpline& s, const glm::dvec3& x) {
  const TensorBasis<K> t(s, x, true);
  const AxisBasis<K>&bx = t.x, &by = t.y, &bz = t.z;
  double v = 0, dx = 0, dy = 0, dz = 0, dxx = 0, dyy = 0, dzz = 0, dxy = 0, dxz = 0, dyz = 0;
  for (int c = 0; c < K; ++c) {
    double yv = 0, yx = 0, yy = 0, yxx = 0, yyy = 0, yxy = 0;
    for (int b = 0; b < K; ++b) {
      const float* row = t.row(b, c);
      double s0 = 0, s1 = 0, s2 = 0;
      for (int a = 0; a < K; ++a) {
        const double p = row[bx.idx[a]];
        s0 += bx.w[a] * p, s1 += bx.dw[a] * p, s2 += bx.d2w[a] * p;
      }
      yv += by.w[b] * s0, yx += by.w[b] * s1, yxx += by.w[b] * s2;
      yy += by.dw[b] * s0, yxy += by.dw[b] * s1, yyy += by.d2w[b] * s0;
    }
    const double w = bz.w[c], dw = bz.dw[c], d2w = bz.d2w[c];
    v += w * yv, dx += w * yx, dy += w * yy, dxx += w * yxx, dyy += w * yyy, dxy += w * yxy;
    dz += dw * yv, dxz += dw * yx, dyz += dw * yy, dzz += d2w * yv;
  }
  return make_jet(v, dx, dy, dz, dxx, dyy, dzz, dxy, dxz, dyz);
}

#if defined(__SSE2__)
// The four control points of the cubic x-row at (b, c), as floats.
inline __m128 load_row4(const TensorBasis<4>& t, int b, int c) {
  const float* row = t.row(b, c);
  const AxisBasis<4>& bx = t.x;
  if (bx.idx[3] - bx.idx[0] == 3) return _mm_loadu_ps(row + bx.idx[0]);
  return _mm_setr_ps(row[bx.idx[0]], row[bx.idx[1]], row[bx.idx[2]], row[bx.idx[3]]);
}

// The cubic jet with SSE2 pairs of doubles: per x-row the pairs (Σ w·p, Σ w′·p) and Σ w″·p, then y and z with the
// partial sums paired so that each multiply-add updates two results. Same operations as jet_k<4>, in another order.
VolumeJet jet_cubic_sse2(const VolumeSpline& s, const glm::dvec3& x) {
  const TensorBasis<4> t(s, x, true);
  const AxisBasis<4>&bx = t.x, &by = t.y, &bz = t.z;
  __m128d wdw[4];  // (w_a, w′_a)
  for (int a = 0; a < 4; ++a) wdw[a] = _mm_setr_pd(bx.w[a], bx.dw[a]);
  const __m128d d2w01 = _mm_setr_pd(bx.d2w[0], bx.d2w[1]), d2w23 = _mm_setr_pd(bx.d2w[2], bx.d2w[3]);
  __m128d v_dx = _mm_setzero_pd(), dy_dxy = _mm_setzero_pd(), dxx_dyy = _mm_setzero_pd();
  __m128d dz_dxz = _mm_setzero_pd(), dyz_dzz = _mm_setzero_pd();
  for (int c = 0; c < 4; ++c) {
    __m128d yv_yx = _mm_setzero_pd(), yy_yxy = _mm_setzero_pd(), yxx_yyy = _mm_setzero_pd();
    for (int b = 0; b < 4; ++b) {
      const __m128 pf = load_row4(t, b, c);
      const __m128d p01 = _mm_cvtps_pd(pf), p23 = _mm_cvtps_pd(_mm_movehl_ps(pf, pf));
      // (s0, s1) = Σ_a p_a·(w_a, w′_a); s2 = Σ_a p_a·w″_a.
      const __m128d s01 = _mm_add_pd(
          _mm_add_pd(_mm_mul_pd(_mm_unpacklo_pd(p01, p01), wdw[0]), _mm_mul_pd(_mm_unpackhi_pd(p01, p01), wdw[1])),
          _mm_add_pd(_mm_mul_pd(_mm_unpacklo_pd(p23, p23), wdw[2]), _mm_mul_pd(_mm_unpackhi_pd(p23, p23), wdw[3])));
      const __m128d t2 = _mm_add_pd(_mm_mul_pd(p01, d2w01), _mm_mul_pd(p23, d2w23));
      const __m128d s2 = _mm_add_sd(t2, _mm_unpackhi_pd(t2, t2));  // low lane: s2
      const __m128d wb = _mm_set1_pd(by.w[b]), dwb = _mm_set1_pd(by.dw[b]);
      yv_yx = _mm_add_pd(yv_yx, _mm_mul_pd(wb, s01));
      yy_yxy = _mm_add_pd(yy_yxy, _mm_mul_pd(dwb, s01));
      // (yxx, yyy) += (w_b·s2, w″_b·s0)
      yxx_yyy = _mm_add_pd(yxx_yyy, _mm_mul_pd(_mm_setr_pd(by.w[b], by.d2w[b]), _mm_unpacklo_pd(s2, s01)));
    }
    const __m128d wc = _mm_set1_pd(bz.w[c]), dwc = _mm_set1_pd(bz.dw[c]);
    v_dx = _mm_add_pd(v_dx, _mm_mul_pd(wc, yv_yx));
    dy_dxy = _mm_add_pd(dy_dxy, _mm_mul_pd(wc, yy_yxy));
    dxx_dyy = _mm_add_pd(dxx_dyy, _mm_mul_pd(wc, yxx_yyy));
    dz_dxz = _mm_add_pd(dz_dxz, _mm_mul_pd(dwc, yv_yx));
    // (dyz, dzz) += (w′_c·yy, w″_c·yv)
    dyz_dzz = _mm_add_pd(dyz_dzz, _mm_mul_pd(_mm_setr_pd(bz.dw[c], bz.d2w[c]), _mm_unpacklo_pd(yy_yxy, yv_yx)));
  }
  alignas(16) double r[10];
  _mm_store_pd(r, v_dx);
  _mm_store_pd(r + 2, dy_dxy);
  _mm_store_pd(r + 4, dxx_dyy);
  _mm_store_pd(r + 6, dz_dxz);
  _mm_store_pd(r + 8, dyz_dzz);
  // r: v, dx, dy, dxy, dxx, dyy, dz, dxz, dyz, dzz
  return make_jet(r[0], r[1], r[2], r[6], r[4], r[5], r[9], r[3], r[7], r[8]);
}

// The cubic value with SSE2 pairs: each x-row's products summed in two lanes, which the y and z weights scale alike,
// and the lanes added at the end. The same products as value_k<4>, summed in another order.
double value_cubic_sse2(const VolumeSpline& s, const glm::dvec3& x) {
  const TensorBasis<4> t(s, x, false);
  const AxisBasis<4>&bx = t.x, &by = t.y, &bz = t.z;
  const __m128d w01 = _mm_setr_pd(bx.w[0], bx.w[1]), w23 = _mm_setr_pd(bx.w[2], bx.w[3]);
  __m128d sum = _mm_setzero_pd();
  for (int c = 0; c < 4; ++c) {
    __m128d sy = _mm_setzero_pd();
    for (int b = 0; b < 4; ++b) {
      const __m128 pf = load_row4(t, b, c);
      const __m128d sx =
          _mm_add_pd(_mm_mul_pd(_mm_cvtps_pd(pf), w01), _mm_mul_pd(_mm_cvtps_pd(_mm_movehl_ps(pf, pf)), w23));
      sy = _mm_add_pd(sy, _mm_mul_pd(_mm_set1_pd(by.w[b]), sx));
    }
    sum = _mm_add_pd(sum, _mm_mul_pd(_mm_set1_pd(bz.w[c]), sy));
  }
  return _mm_cvtsd_f64(_mm_add_sd(sum, _mm_unpackhi_pd(sum, sum)));
}

#endif

// The tri-cubic value and jet: in SSE2 pairs where the target has them.
double value_cubic(const VolumeSpline& s, const glm::dvec3& x) {
#if defined(__SSE2__)
  return value_cubic_sse2(s, x);
#else
  return value_k<4>(s, x);
#endif
}

VolumeJet jet_cubic(const VolumeSpline& s, const glm::dvec3& x) {
#if defined(__SSE2__)
  return jet_cubic_sse2(s, x);
#else
  return jet_k<4>(s, x);
#endif
}

}  // namespace

double VolumeSpline::value(const glm::dvec3& x) const {
  return with_volume_order(order_, [&](auto k) {
    if constexpr (k == 4)
      return value_cubic(*this, x);
    else
      return value_k<k>(*this, x);
  });
}

VolumeJet VolumeSpline::jet(const glm::dvec3& x) const {
  return with_volume_order(order_, [&](auto k) {
    if constexpr (k == 4)
      return jet_cubic(*this, x);
    else
      return jet_k<k>(*this, x);
  });
}

glm::dvec3 VolumeSpline::world_gradient(const glm::dvec3& g) const { return gradient_to_world_ * g; }

namespace {

template <int K>
void bezier_coefficients_k(const VolumeSpline& s, const std::array<double, 16>& to_bezier, int s0, int s1, int s2,
                           double* out) {
  static_assert(K >= 2 && K <= 4);
  bezier_cell::Matrix<K> m;
  for (int a = 0; a < K; ++a)
    for (int r = 0; r < K; ++r) m[a][r] = to_bezier[a * K + r];
  const auto& dims = s.dims();
  int idx[3][K];
  const int cell[3] = {s0, s1, s2};
  for (int a = 0; a < 3; ++a)
    for (int r = 0; r < K; ++r) idx[a][r] = std::clamp(s.first_control(cell[a]) + r, 0, dims[a] - 1);
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  const float* cp = s.control_points().data();
  double p[K * K * K];
  for (int c = 0; c < K; ++c)
    for (int b = 0; b < K; ++b) {
      const float* row = cp + idx[2][c] * nxy + idx[1][b] * nx;
      for (int a = 0; a < K; ++a) p[a + K * (b + K * c)] = row[idx[0][a]];
    }
  bezier_cell::apply3<K>(m, m, m, p, out);
}

}  // namespace

void VolumeSpline::bezier_coefficients(int s0, int s1, int s2, double* out) const {
  with_volume_order(order_, [&](auto k) { bezier_coefficients_k<k>(*this, to_bezier_, s0, s1, s2, out); });
}

}  // namespace trispline::core
