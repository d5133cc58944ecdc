// Shared helpers for the spline tests: seeded random knot vectors / control points, sampling, error checks.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core::test {

using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
inline int uniform_int(Rng& rng, int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); }

// Random valid knot vector with `order` and `n` controls. Interior knots get random multiplicities in
// [1, max_mult] (max_mult <= order). clamped = false gives random (unclamped) end knots as well.
inline KnotVector random_knots(Rng& rng, int order, int n, bool clamped, int max_mult) {
  for (;;) {
    std::vector<double> k;
    const int total = n + order;
    const int free = clamped ? n - order : total;
    const double lo = clamped ? 0.02 : -0.6, hi = clamped ? 0.98 : 1.6;
    while (static_cast<int>(k.size()) < free) {
      const int m = std::min(uniform_int(rng, 1, max_mult), free - static_cast<int>(k.size()));
      const double v = uniform(rng, lo, hi);
      for (int i = 0; i < m; ++i) k.push_back(v);
    }
    std::sort(k.begin(), k.end());
    if (clamped) {
      k.insert(k.begin(), order, 0.0);
      k.insert(k.end(), order, 1.0);
    }
    try {
      return KnotVector(order, k);
    } catch (const std::invalid_argument&) {
      // multiplicity collision or empty domain: draw again
    }
  }
}

template <class T>
T random_point(Rng& rng);
template <>
inline double random_point<double>(Rng& rng) {
  return uniform(rng, -1, 1);
}
template <>
inline glm::dvec2 random_point<glm::dvec2>(Rng& rng) {
  return {uniform(rng, -1, 1), uniform(rng, -1, 1)};
}
template <>
inline glm::dvec3 random_point<glm::dvec3>(Rng& rng) {
  return {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
}

template <class T>
std::vector<T> random_points(Rng& rng, std::size_t count) {
  std::vector<T> p(count);
  for (auto& x : p) x = random_point<T>(rng);
  return p;
}

inline double norm_inf(double x) { return std::abs(x); }
template <int L>
double norm_inf(const glm::vec<L, double>& v) {
  double m = 0;
  for (int c = 0; c < L; ++c) m = std::max(m, std::abs(v[c]));
  return m;
}

// Parameters for sampling a knot vector's domain: random points, every knot in the domain and both ends.
inline std::vector<double> sample_params(Rng& rng, const KnotVector& kv, int random_count) {
  std::vector<double> t;
  for (int i = 0; i < random_count; ++i) t.push_back(uniform(rng, kv.domain_min(), kv.domain_max()));
  for (double k : kv.knots())
    if (k >= kv.domain_min() && k <= kv.domain_max()) t.push_back(k);
  return t;
}

// Random parameter at least `margin` away from every knot (for finite differences across smooth pieces).
inline double param_away_from_knots(Rng& rng, const KnotVector& kv, double margin) {
  for (;;) {
    const double t = uniform(rng, kv.domain_min() + margin, kv.domain_max() - margin);
    bool ok = true;
    for (double k : kv.knots()) ok = ok && std::abs(t - k) > margin;
    if (ok) return t;
  }
}

// Expects fn() to throw std::invalid_argument whose message contains `needle`.
inline void expect_invalid(const std::function<void()>& fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "expected std::invalid_argument mentioning '" << needle << "', nothing was thrown";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message '" << e.what() << "' does not mention '" << needle << "'";
  }
}

}  // namespace trispline::core::test
