// FfdPackedLattice (the float tables every float backend shares): evaluating them exactly as ffd_packed.h specifies,
// in a plain scalar loop, reproduces the double reference ffd_evaluate (positions and normals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/ffd/ffd_packed.h"
#include "ffd_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

// Basis values and d/dt of one axis at t, following the header comment step by step; returns first_index[s].
int packed_basis(const FfdPackedAxis& a, float t, float* N, float* dN) {
  if (a.periodic) t -= std::floor(t);
  t = t >= a.domain_min ? t : a.domain_min;
  t = t <= a.domain_max ? t : a.domain_max;
  const int S = a.span_count();
  int s;
  if (a.uniform_spans) {
    s = std::clamp(static_cast<int>(std::floor((t - a.domain_min) * a.inv_uniform_len)), 0, S - 1);
    if (t < a.span_begin[s])
      --s;
    else if (s + 1 < S && t >= a.span_begin[s + 1])
      ++s;
  } else {
    s = 0;
    while (s + 1 < S && a.span_begin[s + 1] <= t) ++s;
  }
  const float x = (t - a.span_begin[s]) * a.inv_span_len[s];
  const int o = a.order;
  for (int r = 0; r < o; ++r) {
    float v = 0.0f, d = 0.0f;
    for (int k = o - 1; k >= 0; --k) {
      const float c = a.coef[(static_cast<std::size_t>(s) * o + k) * o + r];
      d = d * x + v;  // derivative of the Horner polynomial so far
      v = v * x + c;
    }
    N[r] = v;
    dN[r] = d * a.inv_span_len[s];
  }
  return a.first_index[s];
}

struct PackedResult {
  glm::dvec3 position, normal;
};

PackedResult eval_packed(const FfdPackedLattice& P, const glm::dvec3& uvw, const glm::dvec3& n) {
  float N[3][4], dN[3][4];
  int first[3];
  for (int a = 0; a < 3; ++a) first[a] = packed_basis(P.axes[a], static_cast<float>(uvw[a]), N[a], dN[a]);
  const int l = P.axes[0].count, m = P.axes[1].count;
  glm::vec3 val(0.0f), du(0.0f), dv(0.0f), dw(0.0f);
  for (int k = 0; k < P.axes[2].order; ++k)
    for (int j = 0; j < P.axes[1].order; ++j)
      for (int i = 0; i < P.axes[0].order; ++i) {
        int idx[3] = {first[0] + i, first[1] + j, first[2] + k};
        for (int a = 0; a < 3; ++a)
          if (P.axes[a].periodic) idx[a] %= P.axes[a].count;
        const float* c = &P.control_points[4 * (static_cast<std::size_t>(idx[0]) + l * (idx[1] + m * idx[2]))];
        const glm::vec3 q(c[0], c[1], c[2]);
        val += N[0][i] * N[1][j] * N[2][k] * q;
        du += dN[0][i] * N[1][j] * N[2][k] * q;
        dv += N[0][i] * dN[1][j] * N[2][k] * q;
        dw += N[0][i] * N[1][j] * dN[2][k] * q;
      }
  const glm::mat3 M = glm::mat3(du, dv, dw) * P.embedding_linear;
  const glm::mat3 cof(glm::cross(M[1], M[2]), glm::cross(M[2], M[0]), glm::cross(M[0], M[1]));
  const glm::vec3 nn = cof * glm::vec3(n);
  return {P.centre + glm::dvec3(val), glm::dvec3(glm::normalize(nn))};
}

double angle(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

void expect_packed_matches_reference(const TrivariateBSpline<glm::dvec3>& F, const Embedding& e, const char* what) {
  const FfdPackedLattice P = FfdPackedLattice::build(F, e);
  auto pts = random_points(3000, {-0.3, -0.05, -0.05}, {1.3, 1.05, 1.05}, 11);  // some outside the domain
  pts.push_back({0.5, 0.5, 0.5});
  pts.push_back({1.0, 1.0, 1.0});
  std::vector<glm::dvec3> normals;
  for (std::size_t i = 0; i < pts.size(); ++i) normals.push_back(glm::normalize(glm::dvec3(1.0, 0.3 * i, -0.7)));
  std::vector<glm::dvec3> rp, rn;
  ffd_evaluate(F, e, pts, normals, rp, rn);
  const double diag = P.bbox_diagonal();
  double ep = 0, en = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const PackedResult r = eval_packed(P, pts[i], normals[i]);
    ep = std::max(ep, glm::length(r.position - rp[i]) / diag);
    en = std::max(en, angle(r.normal, rn[i]));
  }
  EXPECT_LE(ep, 1e-5) << what;
  EXPECT_LE(en, 1e-4) << what;
}

}  // namespace

TEST(FfdPacked, TablesEvaluateLikeTheReference) {
  const std::vector<glm::dvec3> box{{-1, 0, 2}, {3, 2, 3}};
  const Embedding e = embed_bounding_box(box, {0, 1});
  for (int o = 2; o <= 4; ++o) {
    expect_packed_matches_reference(bent_lattice(e, KnotVector::clamped_uniform(o, 6),
                                                 KnotVector::clamped_uniform(o, 5), KnotVector::clamped_uniform(o, 4)),
                                    e, "clamped uniform");
    expect_packed_matches_reference(
        bent_lattice(e, KnotVector::uniform(o, 6), KnotVector::uniform(o, 5), KnotVector::uniform(o, 7)), e,
        "floating uniform");
    std::vector<double> k(static_cast<std::size_t>(7 + o), 0.0);  // non-uniform clamped, 7 controls
    for (int i = 0; i < 7 + o; ++i) k[i] = i < o ? 0.0 : i >= 7 ? 1.0 : std::pow((i - o + 1.0) / (8.0 - o), 1.7);
    const KnotVector nu(o, k);
    EXPECT_FALSE(nu.has_uniform_spans());
    expect_packed_matches_reference(bent_lattice(e, nu, KnotVector::clamped_uniform(o, 4), nu), e, "non-uniform");
    expect_packed_matches_reference(random_lattice(KnotKind::periodic_u, {o, 3, 4}, 7), e, "periodic along u");
  }
}

TEST(FfdPacked, LayoutAndErrors) {
  const Embedding e;
  const auto F = bent_lattice(e, KnotVector::clamped_uniform(3, 5), KnotVector::clamped_uniform(2, 3),
                              KnotVector::clamped_uniform(4, 4));
  const FfdPackedLattice P = FfdPackedLattice::build(F, e);
  EXPECT_EQ(P.control_points.size(), 4u * 5 * 3 * 4);
  EXPECT_EQ(P.axes[0].span_count(), 3);
  EXPECT_EQ(P.axes[0].span_begin.size(), 4u);
  EXPECT_EQ(P.axes[0].coef.size(), 3u * 9);
  EXPECT_TRUE(P.axes[0].uniform_spans);
  EXPECT_FLOAT_EQ(P.axes[0].inv_uniform_len, 3.0f);
  const glm::dvec3 p = F.control_point(2, 1, 3) - P.centre;
  const std::size_t idx = 4 * (2 + 5 * (1 + 3 * 3));
  EXPECT_FLOAT_EQ(P.control_points[idx + 1], static_cast<float>(p.y));
  EXPECT_EQ(P.control_points[idx + 3], 0.0f);
  const auto F5 = bent_lattice(e, KnotVector::clamped_uniform(5, 5), KnotVector::clamped_uniform(2, 3),
                               KnotVector::clamped_uniform(4, 4));
  EXPECT_THROW(FfdPackedLattice::build(F5, e), std::invalid_argument);
}
