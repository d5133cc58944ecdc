// KnotVector: factories, validation messages, span search, Greville abscissae.
#include <limits>

#include "core/spline/knot_vector.h"
#include "spline_test_util.h"

namespace trispline::core {
namespace {

using test::expect_invalid;

TEST(KnotVector, ClampedUniformLayout) {
  const KnotVector kv = KnotVector::clamped_uniform(3, 5);  // quadratic, 3 spans
  const std::vector<double> expected = {0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1};
  ASSERT_EQ(kv.knots().size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_DOUBLE_EQ(kv[static_cast<int>(i)], expected[i]);
  EXPECT_EQ(kv.order(), 3);
  EXPECT_EQ(kv.degree(), 2);
  EXPECT_EQ(kv.control_count(), 5);
  EXPECT_EQ(kv.domain_min(), 0.0);
  EXPECT_EQ(kv.domain_max(), 1.0);
  EXPECT_TRUE(kv.is_clamped());
  EXPECT_TRUE(kv.has_uniform_spans());
}

TEST(KnotVector, FloatingUniformHasUnitDomain) {
  const KnotVector kv = KnotVector::uniform(4, 7);
  EXPECT_DOUBLE_EQ(kv.domain_min(), 0.0);
  EXPECT_DOUBLE_EQ(kv.domain_max(), 1.0);
  EXPECT_FALSE(kv.is_clamped());
  EXPECT_TRUE(kv.has_uniform_spans());
  for (int i = 1; i < 11; ++i) EXPECT_NEAR(kv[i] - kv[i - 1], 0.25, 1e-15);
}

TEST(KnotVector, NonUniformSpansDetected) {
  EXPECT_FALSE(KnotVector(2, {0, 0, 0.3, 1, 1}).has_uniform_spans());
  // Empty spans (a double interior knot) do not break uniformity of the non-empty ones.
  EXPECT_TRUE(KnotVector(3, {0, 0, 0, 0.5, 0.5, 1, 1, 1}).has_uniform_spans());
}

TEST(KnotVector, GrevilleOfClampedUniform) {
  // Cubic, 6 controls: knots 0,0,0,0,1/3,2/3,1,1,1,1 → averages of 3 consecutive knots.
  const std::vector<double> g = KnotVector::clamped_uniform(4, 6).greville();
  const std::vector<double> expected = {0, 1.0 / 9, 1.0 / 3, 2.0 / 3, 8.0 / 9, 1};
  ASSERT_EQ(g.size(), expected.size());
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(g[i], expected[i], 1e-15) << i;
  // Linear: Greville = the interior knots themselves. Order 1: span midpoints.
  const std::vector<double> g2 = KnotVector::clamped_uniform(2, 3).greville();
  EXPECT_NEAR(g2[1], 0.5, 1e-15);
  const std::vector<double> g1 = KnotVector::clamped_uniform(1, 4).greville();
  EXPECT_NEAR(g1[0], 0.125, 1e-15);
  EXPECT_NEAR(g1[3], 0.875, 1e-15);
}

TEST(KnotVector, FindSpan) {
  const KnotVector kv(3, {0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1});  // spans 2: [0,.25) 3: [.25,.5) 5: [.5,1]
  EXPECT_EQ(kv.find_span(0.0), 2);
  EXPECT_EQ(kv.find_span(0.1), 2);
  EXPECT_EQ(kv.find_span(0.25), 3);
  EXPECT_EQ(kv.find_span(0.49), 3);
  EXPECT_EQ(kv.find_span(0.5), 5);   // skips the empty span 4
  EXPECT_EQ(kv.find_span(1.0), 5);   // domain end → last non-empty span
  EXPECT_EQ(kv.find_span(-3.0), 2);  // clamped
  EXPECT_EQ(kv.find_span(7.0), 5);
  EXPECT_EQ(kv.multiplicity(0.5), 2);
  EXPECT_EQ(kv.multiplicity(0.0), 3);
  EXPECT_EQ(kv.multiplicity(0.3), 0);
  expect_invalid([&] { kv.find_span(std::numeric_limits<double>::quiet_NaN()); }, "NaN");
}

TEST(KnotVector, LastSpanSkipsTrailingEmptySpans) {
  const KnotVector kv(2, {0, 0.5, 1, 1, 2});  // n = 3: domain [0.5, 1]; span 2 = [1, 1) is empty
  EXPECT_EQ(kv.find_span(1.0), 1);
  EXPECT_EQ(kv.find_span(0.99), 1);
}

TEST(KnotVector, InvalidInputHasClearMessages) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid([] { KnotVector(0, {0, 1}); }, "order must be >= 1");
  expect_invalid([] { KnotVector(4, {0, 0, 0, 0, 1, 1, 1}); }, "exceeds control count");
  expect_invalid([] { KnotVector::clamped_uniform(5, 3); }, "order 5 exceeds control count 3");
  expect_invalid([] { KnotVector::uniform(3, 2); }, "exceeds control count");
  expect_invalid([] { KnotVector(2, {0, 0, 0.7, 0.4, 1, 1}); }, "non-decreasing");
  expect_invalid([&] { KnotVector(2, {0, 0, nan, 1, 1}); }, "not finite");
  expect_invalid([] { KnotVector(2, {0, 0, 0, 1, 1}); }, "multiplicity");
  expect_invalid([] { KnotVector(2, {0, 1, 1, 2}); }, "empty domain");
  expect_invalid([] { KnotVector::clamped_for_fit(3, 6, {0, 0.5, 1}); }, "need at least as many points");
}

TEST(KnotVector, ClampedForFitPutsDataInEverySpan) {
  test::Rng rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const int order = test::uniform_int(rng, 1, 5);
    const int n = test::uniform_int(rng, order, order + 8);
    const int P = test::uniform_int(rng, n, 4 * n);
    std::vector<double> params(P);
    for (auto& t : params) t = test::uniform(rng, 0, 1);
    std::sort(params.begin(), params.end());
    params.front() = 0;
    params.back() = 1;
    const KnotVector kv = KnotVector::clamped_for_fit(order, n, params);
    EXPECT_TRUE(kv.is_clamped());
    EXPECT_EQ(kv.control_count(), n);
    for (int s = order - 1; s < n; ++s) {
      if (kv[s] == kv[s + 1]) continue;
      const bool hit = std::any_of(params.begin(), params.end(), [&](double t) {
        return t >= kv[s] && (t < kv[s + 1] || (s + 1 == n && t <= kv[s + 1]));
      });
      EXPECT_TRUE(hit) << "span " << s << " has no parameter";
    }
  }
}

}  // namespace
}  // namespace trispline::core
