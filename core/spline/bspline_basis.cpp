// Cox–de Boor basis functions and derivatives: Piegl & Tiller A2.2 (BasisFuns) and A2.3 (DersBasisFuns).
#include "core/spline/bspline_basis.h"

#include <algorithm>

#include "core/spline/scratch.h"

namespace trispline::core {

void basis_functions(const KnotVector& kv, int span, double t, double* N) {
  const int p = kv.degree();
  const double* U = kv.knots().data();
  detail::Scratch<32> tmp(2 * static_cast<std::size_t>(p + 1));
  double* left = tmp.data();
  double* right = left + (p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

void basis_derivatives(const KnotVector& kv, int span, double t, int n_deriv, double* ders) {
  const int p = kv.degree();
  const int k1 = p + 1;
  const double* U = kv.knots().data();
  const int nd = std::min(n_deriv, p);
  // ndu: (p+1)² triangle of basis values (lower) and knot differences (upper); a: two rows of (p+1).
  detail::Scratch<128> tmp(static_cast<std::size_t>(k1 * k1 + 4 * k1));
  double* ndu = tmp.data();
  double* a = ndu + k1 * k1;
  double* left = a + 2 * k1;
  double* right = left + k1;
  auto NDU = [&](int i, int j) -> double& { return ndu[i * k1 + j]; };

  NDU(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      NDU(j, r) = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = NDU(r, j - 1) / NDU(j, r);
      NDU(r, j) = saved + right[r + 1] * temp;  // upper triangle: basis functions
      saved = left[j - r] * temp;
    }
    NDU(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = NDU(j, p);

  for (int r = 0; r <= p; ++r) {
    double* a1 = a;
    double* a2 = a + k1;
    a1[0] = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a2[0] = a1[0] / NDU(pk + 1, rk);
        d = a2[0] * NDU(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a2[j] = (a1[j] - a1[j - 1]) / NDU(pk + 1, rk + j);
        d += a2[j] * NDU(rk + j, pk);
      }
      if (r <= pk) {
        a2[k] = -a1[k - 1] / NDU(pk + 1, r);
        d += a2[k] * NDU(r, pk);
      }
      ders[k * k1 + r] = d;
      std::swap(a1, a2);
    }
  }
  // Multiply through by p! / (p-k)!.
  double f = p;
  for (int k = 1; k <= nd; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * k1 + j] *= f;
    f *= (p - k);
  }
  for (int k = nd + 1; k <= n_deriv; ++k)
    for (int j = 0; j <= p; ++j) ders[k * k1 + j] = 0.0;
}

void basis_first_derivatives(const KnotVector& kv, int span, double t, double* N, double* dN) {
  const int p = kv.degree();
  if (p == 0) {
    N[0] = 1.0;
    dN[0] = 0.0;
    return;
  }
  const double* U = kv.knots().data();
  // A2.2 up to degree p − 1 (N[0..p)), saved as `prev`, then its last step to degree p: the same operations as
  // A2.3's table (its upper triangle is A2.2's rows, its lower triangle the knot differences `diff` of each step).
  detail::Scratch<48> tmp(4 * static_cast<std::size_t>(p + 1));
  double* left = tmp.data();
  double* right = left + (p + 1);
  double* prev = right + (p + 1);
  double* diff = prev + (p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    if (j == p) std::copy(N, N + p, prev);
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double d = right[r + 1] + left[j - r];
      if (j == p) diff[r] = d;
      const double temp = N[r] / d;
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  // A2.3, k = 1: a2[0] = 1/diff[r−1] (r ≥ 1), a2[1] = −1/diff[r] (r ≤ p − 1); times p.
  detail::first_derivative_row(p, prev, diff, dN);
}

}  // namespace trispline::core
