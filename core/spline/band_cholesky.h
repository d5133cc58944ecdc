// trispline::core::BandCholesky — Cholesky factorisation A = L·Lᵀ of a symmetric positive-definite band matrix,
// used to solve the normal equations of least-squares B-spline fitting (the matrix NᵀN has half-bandwidth
// degree = order − 1, Piegl & Tiller ch. 9.4.1). Cost O(n·b²); right-hand sides of any vector type T.
// Source: Golub & Van Loan, Matrix Computations, Alg. 4.3.5 (band Cholesky).
#pragma once

#include <cstddef>
#include <vector>

namespace trispline::core {

class BandCholesky {
 public:
  // band: #n·(b+1) lower band of A, band[i·(b+1) + d] = A(i, i−d) for d ∈ [0, b] (entries with i−d < 0 ignored).
  // Throws std::invalid_argument if n < 0, b < 0, the size is wrong, or A is not (numerically) positive definite:
  // a pivot ≤ 1e-14 · max diagonal (in fitting: a basis function with no data in its support).
  BandCholesky(int n, int b, std::vector<double> band);

  int size() const { return n_; }

  // Solves A·x = rhs in place; rhs holds #n values of T (double, glm::dvec2, glm::dvec3, …).
  template <class T>
  void solve(T* rhs) const {
    for (int i = 0; i < n_; ++i) {  // L·y = rhs
      T s = rhs[i];
      for (int d = 1; d <= b_ && d <= i; ++d) s -= rhs[i - d] * L(i, d);
      rhs[i] = s / L(i, 0);
    }
    for (int i = n_ - 1; i >= 0; --i) {  // Lᵀ·x = y
      T s = rhs[i];
      for (int d = 1; d <= b_ && i + d < n_; ++d) s -= rhs[i + d] * L(i + d, d);
      rhs[i] = s / L(i, 0);
    }
  }

 private:
  double L(int i, int d) const { return l_[static_cast<std::size_t>(i) * (b_ + 1) + d]; }
  int n_, b_;
  std::vector<double> l_;  // same layout as `band`: l_[i·(b+1) + d] = L(i, i−d)
};

}  // namespace trispline::core
