// Basis functions (P&T A2.2) and derivatives (A2.3): partition of unity, agreement of the two algorithms, known
// values, derivatives against central differences.
#include "core/spline/bspline_basis.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

TEST(Basis, PartitionOfUnityAndNonNegativity) {
  test::Rng rng(1);
  for (int order = 1; order <= 6; ++order) {
    for (int trial = 0; trial < 20; ++trial) {
      const int n = test::uniform_int(rng, order, order + 6);
      const KnotVector kv = test::random_knots(rng, order, n, trial % 2 == 0, order);
      std::vector<double> N(order);
      for (double t : test::sample_params(rng, kv, 50)) {
        basis_functions(kv, kv.find_span(t), t, N.data());
        double sum = 0;
        for (double b : N) {
          EXPECT_GE(b, -1e-15);
          sum += b;
        }
        EXPECT_NEAR(sum, 1.0, 1e-13) << "order " << order << " t " << t;
      }
    }
  }
}

TEST(Basis, KnownCubicValuesOnUniformKnots) {
  // Uniform cubic B-spline at the start of an interior span: (1/6, 2/3, 1/6, 0); at the middle: (1,23,23,1)/48.
  const KnotVector kv = KnotVector::uniform(4, 8);
  const double h = kv[1] - kv[0];
  const int span = 5;
  std::vector<double> N(4);
  basis_functions(kv, span, kv[span], N.data());
  EXPECT_NEAR(N[0], 1.0 / 6, 1e-15);
  EXPECT_NEAR(N[1], 2.0 / 3, 1e-15);
  EXPECT_NEAR(N[2], 1.0 / 6, 1e-15);
  EXPECT_NEAR(N[3], 0.0, 1e-15);
  basis_functions(kv, span, kv[span] + 0.5 * h, N.data());
  EXPECT_NEAR(N[0], 1.0 / 48, 1e-15);
  EXPECT_NEAR(N[1], 23.0 / 48, 1e-15);
  EXPECT_NEAR(N[2], 23.0 / 48, 1e-15);
  EXPECT_NEAR(N[3], 1.0 / 48, 1e-15);
}

// basis_first_derivatives is A2.3 restricted to k = 1 with the same arithmetic: bit-identical to
// basis_derivatives(·, 1, ·) (values and first derivatives), on random knots with repeated (up to C⁻¹) knots.
TEST(Basis, FirstDerivativesBitIdenticalToDersBasisFuns) {
  test::Rng rng(5);
  for (int order = 1; order <= 6; ++order)
    for (int trial = 0; trial < 4; ++trial) {
      const KnotVector kv = test::random_knots(rng, order, order + 5, false, order);
      std::vector<double> N(order), dN(order), D(2 * order);
      for (double t : test::sample_params(rng, kv, 40)) {
        const int s = kv.find_span(t);
        basis_first_derivatives(kv, s, t, N.data(), dN.data());
        basis_derivatives(kv, s, t, 1, D.data());
        for (int r = 0; r < order; ++r) {
          EXPECT_EQ(N[r], D[r]) << "order " << order << " t " << t << " r " << r;
          EXPECT_EQ(dN[r], D[order + r]) << "order " << order << " t " << t << " r " << r;
        }
      }
    }
}

TEST(Basis, DerivativeRowZeroEqualsBasisFunctions) {
  test::Rng rng(2);
  for (int order = 1; order <= 6; ++order) {
    const KnotVector kv = test::random_knots(rng, order, order + 4, false, order);
    std::vector<double> N(order), D(3 * order);
    for (double t : test::sample_params(rng, kv, 30)) {
      const int s = kv.find_span(t);
      basis_functions(kv, s, t, N.data());
      basis_derivatives(kv, s, t, 2, D.data());
      double dsum = 0, ddsum = 0;
      for (int r = 0; r < order; ++r) {
        EXPECT_NEAR(D[r], N[r], 1e-14);
        dsum += D[order + r];
        ddsum += D[2 * order + r];
      }
      // Σ B_i ≡ 1, so the derivatives of the sum vanish (scaled by the derivative magnitude).
      double scale = 1;
      for (int r = 0; r < order; ++r) scale = std::max(scale, std::abs(D[2 * order + r]));
      EXPECT_NEAR(dsum, 0.0, 1e-12 * scale);
      EXPECT_NEAR(ddsum, 0.0, 1e-12 * scale);
    }
  }
}

TEST(Basis, DerivativesMatchCentralDifferences) {
  test::Rng rng(3);
  const double h = 1e-6;
  for (int order = 1; order <= 6; ++order) {
    for (int trial = 0; trial < 10; ++trial) {
      const KnotVector kv = test::random_knots(rng, order, order + 5, trial % 2 == 0, order - 1 > 0 ? order - 1 : 1);
      const int nd = 3;
      std::vector<double> D((nd + 1) * order), Dp((nd + 1) * order), Dm((nd + 1) * order);
      for (int sample = 0; sample < 20; ++sample) {
        const double t = test::param_away_from_knots(rng, kv, 1e-3);
        const int s = kv.find_span(t);
        basis_derivatives(kv, s, t, nd, D.data());
        basis_derivatives(kv, s, t + h, nd, Dp.data());
        basis_derivatives(kv, s, t - h, nd, Dm.data());
        for (int d = 1; d <= nd; ++d)
          for (int r = 0; r < order; ++r) {
            const double fd = (Dp[(d - 1) * order + r] - Dm[(d - 1) * order + r]) / (2 * h);
            const double an = D[d * order + r];
            EXPECT_NEAR(an, fd, 1e-5 * (1 + std::abs(an))) << "order " << order << " d " << d << " r " << r;
          }
        for (int r = 0; r < order && order <= nd; ++r) EXPECT_EQ(D[order * order + r], 0.0);  // above the degree
      }
    }
  }
}

}  // namespace
}  // namespace trispline::core
