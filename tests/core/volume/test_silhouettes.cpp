// Singletons (soundness of ranges and cones), the lookup table, Newton convergence and silhouette accuracy on analytic
// volumes whose silhouettes are known circles.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/volume/analytic_volumes.h"
#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(VolumeSpline, InterpolatingSplinePassesThroughTheSamples) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::torus, 16);
  for (int order : {3, 4}) {
    const VolumeSpline s(v, order, /*interpolate=*/true);
    for (int k : {0, 3, 11})
      for (int j : {0, 7, 19})
        for (int i : {0, 5, 15}) EXPECT_NEAR(s.value(glm::dvec3(i, j, k)), v.at(i, j, k), 1e-4) << order;
  }
}

TEST(VolumeSpline, JetMatchesFiniteDifferences) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 12);
  for (int order : {2, 3, 4}) {
    const VolumeSpline s(v, order);
    const glm::dvec3 x(4.3, 6.7, 3.2);
    const VolumeJet j = s.jet(x);
    EXPECT_NEAR(j.value, s.value(x), 1e-12);
    const double h = 1e-5;
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 e(0.0);
      e[a] = h;
      EXPECT_NEAR(j.gradient[a], (s.value(x + e) - s.value(x - e)) / (2 * h), 1e-6) << order << " axis " << a;
      if (order > 2) {
        const glm::dvec3 g = (s.jet(x + e).gradient - s.jet(x - e).gradient) / (2 * h);
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(j.hessian[a][b], g[b], 1e-5) << order;
      }
    }
  }
}

TEST(VolumeSpline, BezierFormEvaluatesToTheSpline) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 10);
  for (int order : {2, 3, 4}) {
    const VolumeSpline s(v, order);
    const int k = order, cell[3] = {3, 4, 2};
    double bez[64];
    s.bezier_coefficients(cell[0], cell[1], cell[2], bez);
    const glm::dvec3 u(0.3, 0.6, 0.85);
    auto bern = [k](int i, double t) {
      double c = 1;
      for (int m = 1; m <= i; ++m) c = c * (k - 1 - i + m) / m;
      return c * std::pow(t, i) * std::pow(1 - t, k - 1 - i);
    };
    double sum = 0;
    for (int c = 0; c < k; ++c)
      for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a) sum += bez[a + k * (b + k * c)] * bern(a, u.x) * bern(b, u.y) * bern(c, u.z);
    const glm::dvec3 x(s.span_begin(cell[0]) + u.x, s.span_begin(cell[1]) + u.y, s.span_begin(cell[2]) + u.z);
    EXPECT_NEAR(sum, s.value(x), 1e-9) << order;
  }
}

// Every sampled value lies in its singleton's range and every sampled gradient direction in its cone.
TEST(Singletons, RangesAndConesHoldEverySample) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::torus, 20);
  for (int order : {2, 3, 4}) {
    const VolumeSpline s(v, order);
    const SingletonTable t = build_singleton_table(s);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int tested_cones = 0;
    for (int n = 0; n < 4000; ++n) {
      const int a = static_cast<int>(u(rng) * t.cells()[0]), b = static_cast<int>(u(rng) * t.cells()[1]),
                c = static_cast<int>(u(rng) * t.cells()[2]);
      glm::dvec3 x(s.span_begin(a) + u(rng), s.span_begin(b) + u(rng), s.span_begin(c) + u(rng));
      x = glm::clamp(x, glm::dvec3(0.0), glm::dvec3(s.dims()[0] - 1, s.dims()[1] - 1, s.dims()[2] - 1));
      const Singleton& sg = t.singletons()[t.cell_index(a, b, c)];
      const VolumeJet j = s.jet(x);
      EXPECT_LE(sg.lo, j.value + 1e-9);
      EXPECT_GE(sg.hi, j.value - 1e-9);
      if (sg.sin_half < 1.0f && glm::length(j.gradient) > 0.0) {
        const double cos_half = std::sqrt(1.0 - double(sg.sin_half) * sg.sin_half);
        const glm::dvec3 axis(sg.axis[0], sg.axis[1], sg.axis[2]);
        EXPECT_GE(glm::dot(axis, glm::normalize(j.gradient)), cos_half - 1e-6);
        ++tested_cones;
      }
    }
    EXPECT_GT(tested_cones, 1000) << "cones should be tight on a smooth field";
  }
}

// The table's singletons (made a slab at a time, the first axis's knot insertion shared between neighbouring cells)
// are singleton_of_cell's, bit for bit, for every order and at the clamped borders.
TEST(Singletons, TableEqualsEachCellAlone) {
  ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 13);
  for (std::size_t i = 0; i < v.values.size(); i += 7) v.values[i] += 0.01f * float(i % 5);  // no symmetry to hide in
  for (int order : {2, 3, 4}) {
    const VolumeSpline s(v, order);
    const SingletonTable t = build_singleton_table(s);
    std::size_t differ = 0;
    for (int c = 0; c < t.cells()[2]; ++c)
      for (int b = 0; b < t.cells()[1]; ++b)
        for (int a = 0; a < t.cells()[0]; ++a) {
          const Singleton alone = singleton_of_cell(s, a, b, c);
          differ += std::memcmp(&alone, &t.singletons()[t.cell_index(a, b, c)], sizeof(Singleton)) != 0;
        }
    EXPECT_EQ(differ, 0u) << "order " << order;
  }
}

TEST(Singletons, TableFindsExactlyTheCellsHoldingALevel) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 18);
  const VolumeSpline s(v, 4);
  // 32 × 16 bins of a few cells each (sorted as 64-bit keys), and one bin of all 4,913 cells (the radix sort).
  for (const auto [rows, columns] : {std::pair{32, 16}, std::pair{1, 1}}) {
    const SingletonTable t = build_singleton_table(s, {}, rows, columns);
    for (double iso : {-0.5, 0.0, 0.31, 0.9}) {
      std::vector<std::uint32_t> expected;
      for (std::size_t i = 0; i < t.cell_count(); ++i) {
        const Singleton& sg = t.singletons()[i];
        if (sg.hi > sg.lo && sg.lo <= iso && iso <= sg.hi) expected.push_back(static_cast<std::uint32_t>(i));
      }
      EXPECT_EQ(t.cells_holding(iso), expected) << iso << " in " << rows << " × " << columns << " bins";
      // The table's own order: by bin, within a bin hi descending and then cell ascending.
      const auto by_bin = t.cells_holding(iso, glm::dvec3(0.0, 0.0, 1.0), 3.2, SingletonTable::CellOrder::by_bin);
      if (rows == 1)
        for (std::size_t k = 1; k < by_bin.size(); ++k) {
          const float h0 = t.singletons()[by_bin[k - 1]].hi, h1 = t.singletons()[by_bin[k]].hi;
          ASSERT_TRUE(h0 > h1 || (h0 == h1 && by_bin[k - 1] < by_bin[k])) << k;
        }
    }
  }
}

TEST(Singletons, CancelThrowsAndProgressIsReported) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 40);
  const VolumeSpline s(v, 4);
  std::atomic<bool> cancel{false};
  double last = -1;
  int calls = 0;
  ProgressSink sink{[&](double f) {
                      EXPECT_GE(f, last);
                      last = f;
                      if (++calls == 3) cancel = true;
                    },
                    &cancel};
  EXPECT_THROW(build_singleton_table(s, sink), OperationCancelled);
  EXPECT_EQ(calls, 3);
}

// Distance from q to the polylines (segments).
double distance_to_polylines(const SilhouetteResult& r, const glm::dvec3& q) {
  double best = INFINITY;
  for (const auto& pl : r.polylines) {
    const std::size_t n = pl.points.size();
    for (std::size_t i = 0; i + 1 < n + (pl.closed ? 1 : 0); ++i) {
      const glm::dvec3 a = pl.points[i], b = pl.points[(i + 1) % n];
      const glm::dvec3 ab = b - a;
      const double t = std::clamp(glm::dot(q - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
      best = std::min(best, glm::length(q - (a + t * ab)));
    }
  }
  return best;
}

struct Circle {
  glm::dvec3 centre, normal;
  double radius;
};

glm::dvec3 circle_point(const Circle& c, double angle) {
  const glm::dvec3 a =
      glm::normalize(glm::cross(c.normal, std::abs(c.normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 b = glm::cross(c.normal, a);
  return c.centre + c.radius * (std::cos(angle) * a + std::sin(angle) * b);
}

// Checks accuracy (every polyline point within tol of the circle) and coverage (≥ 99 % of the circle within tol of a
// polyline) for an exact silhouette circle.
void expect_matches_circle(const SilhouetteResult& r, const Circle& c, double tol) {
  ASSERT_FALSE(r.polylines.empty());
  double worst = 0.0;
  for (const auto& pl : r.polylines)
    for (const glm::dvec3& p : pl.points) {
      const glm::dvec3 d = p - c.centre;
      const double h = glm::dot(d, c.normal);
      const double rho = glm::length(d - h * c.normal);
      worst = std::max(worst, std::hypot(h, rho - c.radius));
    }
  EXPECT_LE(worst, tol);
  const int samples = 2000;
  int covered = 0;
  for (int i = 0; i < samples; ++i)
    if (distance_to_polylines(r, circle_point(c, 2 * kPi * i / samples)) <= tol) ++covered;
  EXPECT_GE(covered, 0.99 * samples) << "coverage " << double(covered) / samples;
}

TEST(Silhouettes, SphereOrthographicIsTheGreatCircle) {
  const AnalyticShape shape;
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 48, shape);
  const VolumeSpline s(v, 4, /*interpolate=*/true);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.perspective = false;
  view.direction = glm::normalize(glm::dvec3(0.3, -0.5, -1.0));
  SilhouetteParams p;
  p.hidden_test = false;
  const SilhouetteResult r = extract_silhouettes(s, t, 0.0, view, p);
  EXPECT_LE(r.max_value_residual, 1e-6);
  EXPECT_LE(r.max_dot_residual, 1e-5);
  expect_matches_circle(r, {glm::dvec3(0.0), glm::normalize(view.direction), shape.sphere_radius},
                        1e-3 * 2 * shape.extent);
  EXPECT_EQ(r.polylines.size(), 1u);
  EXPECT_TRUE(r.polylines[0].closed);
}

TEST(Silhouettes, SpherePerspectiveIsTheSmallerCircle) {
  const AnalyticShape shape;
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 48, shape);
  const VolumeSpline s(v, 4, true);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.eye = glm::dvec3(40.0, 70.0, 130.0);
  const SilhouetteResult r = extract_silhouettes(s, t, 0.0, view);
  const double d = glm::length(view.eye), R = shape.sphere_radius;
  const Circle c{view.eye * (R * R / (d * d)), glm::normalize(view.eye), R * std::sqrt(1 - R * R / (d * d))};
  expect_matches_circle(r, c, 1e-3 * 2 * shape.extent);
  // A sphere's silhouette is never hidden by the sphere itself.
  for (const auto& pl : r.polylines)
    for (unsigned char vis : pl.visible) EXPECT_EQ(vis, 1);
}

TEST(Silhouettes, TorusSideViewHasOuterAndHiddenInnerParts) {
  const AnalyticShape shape;
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::torus, 56, shape);
  const VolumeSpline s(v, 4, true);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.perspective = false;
  view.direction = glm::normalize(glm::dvec3(0.0, -1.0, -0.35));  // oblique: the inner rim is partly hidden
  const SilhouetteResult r = extract_silhouettes(s, t, 0.0, view);
  EXPECT_LE(r.max_value_residual, 1e-6);
  EXPECT_LE(r.max_dot_residual, 1e-5);
  std::size_t hidden = 0, total = 0;
  for (const auto& pl : r.polylines) {
    total += pl.visible.size();
    for (unsigned char vis : pl.visible) hidden += vis ? 0 : 1;
    // Every point is on the torus (within the spline's approximation of the samples).
    for (const glm::dvec3& p : pl.points)
      EXPECT_NEAR(analytic_field(AnalyticVolume::torus, p, shape), 0.0, 1e-3 * 2 * shape.extent);
  }
  EXPECT_GT(hidden, 0u);
  EXPECT_LT(hidden, total);
}

TEST(Silhouettes, DeterministicAndRefusesBadInput) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 24);
  const VolumeSpline s(v, 3);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.eye = glm::dvec3(90.0, 20.0, 60.0);
  const SilhouetteResult a = extract_silhouettes(s, t, 0.2, view), b = extract_silhouettes(s, t, 0.2, view);
  ASSERT_EQ(a.polylines.size(), b.polylines.size());
  for (std::size_t i = 0; i < a.polylines.size(); ++i) EXPECT_EQ(a.polylines[i].points, b.polylines[i].points);
  EXPECT_GT(a.points, 100u);
  EXPECT_THROW(extract_silhouettes(s, t, NAN, view), std::invalid_argument);
  SilhouetteParams p;
  p.subdivision = 9;
  EXPECT_THROW(extract_silhouettes(s, t, 0.2, view, p), std::invalid_argument);
  const VolumeSpline other(make_analytic_volume(AnalyticVolume::sines, 20), 3);
  EXPECT_THROW(extract_silhouettes(other, t, 0.2, view), std::invalid_argument);
}

// Traced curves are continuous: consecutive points of a polyline are at most a step apart (index units), and the
// torus' silhouette comes out as a few long closed curves, not as fragments.
TEST(Silhouettes, TracedPolylinesAreContinuousAndFew) {
  const AnalyticShape shape;
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::torus, 72, shape);
  const VolumeSpline s(v, 4, true);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.eye = glm::dvec3(30.0, 140.0, 90.0);
  SilhouetteParams p;
  p.hidden_test = false;
  const SilhouetteResult r = extract_silhouettes(s, t, 0.0, view, p);
  ASSERT_FALSE(r.polylines.empty());
  EXPECT_LE(r.polylines.size(), 4u) << "a torus seen from above has an outer and an inner rim (and at most two more)";
  double longest = 0.0;
  for (const auto& pl : r.polylines) {
    EXPECT_TRUE(pl.closed);
    for (std::size_t i = 0; i + 1 < pl.points.size(); ++i) {
      const glm::dvec3 a(s.world_to_index() * glm::dvec4(pl.points[i], 1.0));
      const glm::dvec3 b(s.world_to_index() * glm::dvec4(pl.points[i + 1], 1.0));
      longest = std::max(longest, glm::length(b - a));
    }
  }
  EXPECT_LE(longest, 0.6) << "index units between consecutive points";
}

// Blocks are traced in parallel and joined afterwards: one thread and two give the same polylines bit for bit.
TEST(Silhouettes, SameResultForAnyThreadCount) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 70);
  const VolumeSpline s(v, 4);
  const SingletonTable t = build_singleton_table(s);
  SilhouetteView view;
  view.eye = glm::dvec3(120.0, -40.0, 90.0);
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return extract_silhouettes(s, t, 0.15, view);
  };
  const SilhouetteResult a = run(1), b = run(2);
  ASSERT_EQ(a.polylines.size(), b.polylines.size());
  EXPECT_GT(a.polylines.size(), 10u);
  for (std::size_t i = 0; i < a.polylines.size(); ++i) {
    EXPECT_EQ(a.polylines[i].points, b.polylines[i].points);
    EXPECT_EQ(a.polylines[i].visible, b.polylines[i].visible);
  }
}

}  // namespace
}  // namespace trispline::core
