// Band Cholesky factorisation (Golub & Van Loan Alg. 4.3.5) in a fixed operation order.
#include "core/spline/band_cholesky.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace trispline::core {

BandCholesky::BandCholesky(int n, int b, std::vector<double> band) : n_(n), b_(b), l_(std::move(band)) {
  if (n < 0 || b < 0) throw std::invalid_argument("BandCholesky: negative size or bandwidth");
  if (l_.size() != static_cast<std::size_t>(n) * (b + 1))
    throw std::invalid_argument("BandCholesky: band storage has " + std::to_string(l_.size()) + " entries, expected " +
                                std::to_string(static_cast<std::size_t>(n) * (b + 1)));
  auto at = [&](int i, int d) -> double& { return l_[static_cast<std::size_t>(i) * (b_ + 1) + d]; };
  double max_diag = 0.0;
  for (int i = 0; i < n_; ++i) max_diag = std::max(max_diag, std::abs(at(i, 0)));
  const double tiny = 1e-14 * max_diag;
  for (int i = 0; i < n_; ++i) {
    // Row i of L: L(i,j) = (A(i,j) − Σ_{k<j} L(i,k) L(j,k)) / L(j,j), j ∈ [i−b, i).
    for (int d = std::min(b_, i); d >= 1; --d) {
      const int j = i - d;
      double s = at(i, d);
      for (int k = std::max(0, i - b_); k < j; ++k) s -= at(i, i - k) * at(j, j - k);
      at(i, d) = s / at(j, 0);
    }
    double s = at(i, 0);
    for (int k = std::max(0, i - b_); k < i; ++k) s -= at(i, i - k) * at(i, i - k);
    if (!(s > tiny))
      throw std::invalid_argument("BandCholesky: matrix is not positive definite at row " + std::to_string(i) +
                                  " (pivot " + std::to_string(s) + ")");
    at(i, 0) = std::sqrt(s);
  }
}

}  // namespace trispline::core
