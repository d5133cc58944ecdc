// SpanBasis (float/double fast path) against basis_functions / basis_derivatives (the double reference).
#include <limits>

#include "core/spline/bspline_basis.h"
#include "core/spline/span_basis.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

// Compares SpanBasis<Real> with the reference at `ts` (each rounded to Real first); returns the largest error of
// N and of dN relative to max(1, max|dN|).
template <class Real>
std::pair<double, double> compare(const KnotVector& kv, const std::vector<double>& ts) {
  const SpanBasis<Real> fast(kv);
  const int order = kv.order();
  std::vector<Real> N(order), dN(order);
  std::vector<double> ref(2 * order);
  double eN = 0, edN = 0;
  for (double t0 : ts) {
    const Real tr = static_cast<Real>(t0);
    const double t = static_cast<double>(tr);
    const int span = kv.find_span(t);
    const double tc = std::clamp(t, kv.domain_min(), kv.domain_max());
    basis_derivatives(kv, span, tc, 1, ref.data());
    const int first = fast.eval(tr, N.data(), dN.data());
    EXPECT_EQ(first, span - order + 1) << "t = " << t;
    double scale = 1;
    for (int r = 0; r < order; ++r) scale = std::max(scale, std::abs(ref[order + r]));
    for (int r = 0; r < order; ++r) {
      eN = std::max(eN, std::abs(static_cast<double>(N[r]) - ref[r]));
      edN = std::max(edN, std::abs(static_cast<double>(dN[r]) - ref[order + r]) / scale);
    }
    const int first_no_d = fast.eval(tr, N.data(), nullptr);  // dN is optional
    EXPECT_EQ(first_no_d, first);
  }
  return {eN, edN};
}

std::vector<KnotVector> knot_cases(test::Rng& rng, int order) {
  return {KnotVector::clamped_uniform(order, order + 5), KnotVector::uniform(order, order + 3),
          KnotVector::clamped_uniform(order, order),  // single span (Bézier)
          test::random_knots(rng, order, order + 6, true, order), test::random_knots(rng, order, order + 4, false, 1)};
}

TEST(SpanBasis, UniformLookupIsUsedExactlyWhenSpansAreUniform) {
  EXPECT_TRUE(SpanBasis<float>(KnotVector::clamped_uniform(4, 9)).uniform());
  EXPECT_TRUE(SpanBasis<double>(KnotVector::uniform(3, 5)).uniform());
  EXPECT_FALSE(SpanBasis<double>(KnotVector(2, {0, 0, 0.3, 1, 1})).uniform());
  EXPECT_EQ(SpanBasis<double>(KnotVector(3, {0, 0, 0, 0.5, 0.5, 1, 1, 1})).span_count(), 2);
}

TEST(SpanBasis, DoubleAgreesWithReference) {
  test::Rng rng(51);
  for (int order = 1; order <= 6; ++order)
    for (const KnotVector& kv : knot_cases(rng, order)) {
      std::vector<double> ts = test::sample_params(rng, kv, 300);  // includes every knot and both ends
      ts.push_back(kv.domain_min() - 0.5);                         // clamped like find_span
      ts.push_back(kv.domain_max() + 0.5);
      const auto [eN, edN] = compare<double>(kv, ts);
      EXPECT_LE(eN, 1e-12) << "order " << order;
      EXPECT_LE(edN, 1e-12) << "order " << order;
    }
}

TEST(SpanBasis, FloatAgreesWithReference) {
  test::Rng rng(52);
  for (int order = 1; order <= 5; ++order)
    for (const KnotVector& kv : knot_cases(rng, order)) {
      std::vector<double> ts;  // away from knots: float and double may place a knot on different sides
      for (int i = 0; i < 300; ++i) ts.push_back(test::param_away_from_knots(rng, kv, 1e-5));
      ts.push_back(kv.domain_min());
      ts.push_back(kv.domain_max());
      const auto [eN, edN] = compare<float>(kv, ts);
      EXPECT_LE(eN, 1e-5) << "order " << order;
      EXPECT_LE(edN, 1e-5) << "order " << order;
    }
}

TEST(SpanBasis, NanMapsToDomainStart) {
  const KnotVector kv = KnotVector::clamped_uniform(3, 6);
  const SpanBasis<float> fast(kv);
  float N[3], ref[3];
  EXPECT_EQ(fast.eval(std::numeric_limits<float>::quiet_NaN(), N, nullptr), 0);
  fast.eval(0.0f, ref, nullptr);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(N[r], ref[r]);
}

}  // namespace
}  // namespace trispline::core
