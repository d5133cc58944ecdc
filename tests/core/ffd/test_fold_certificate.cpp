// The fold-free certificate: exact on undeformed lattices, finds planted folds where det J really is ≤ 0, never
// certifies a lattice on which dense sampling finds det J ≤ 0 (random lattices of orders 2–4), unwraps periodic axes,
// and refuses what it cannot judge.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/ffd/fold_certificate.h"
#include "core/spline/knot_vector.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {
namespace {

// The identity map on [0,1]³: control points at the Greville abscissae.
TrivariateBSpline<glm::dvec3> identity_lattice(const glm::ivec3& order, const glm::ivec3& controls) {
  const KnotVector ku = KnotVector::clamped_uniform(order.x, controls.x),
                   kv = KnotVector::clamped_uniform(order.y, controls.y),
                   kw = KnotVector::clamped_uniform(order.z, controls.z);
  const auto gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  std::vector<glm::dvec3> P;
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i) P.emplace_back(gu[i], gv[j], gw[k]);
  return TrivariateBSpline<glm::dvec3>(ku, kv, kw, std::move(P));
}

// Smallest det J over an n³ grid of parameters (cell corners and interiors alike).
double sampled_min_det(const TrivariateBSpline<glm::dvec3>& F, int n) {
  double mn = INFINITY;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 t((i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n);
        mn = std::min(mn, jacobian_determinant(F, t));
      }
  return mn;
}

TEST(FoldCertificate, IdentityLatticesAreCertified) {
  for (int order : {2, 3, 4}) {
    const auto F = identity_lattice(glm::ivec3(order), glm::ivec3(order + 3, order + 2, order + 4));
    const FoldCertificate q = certify_fold_free(F);
    EXPECT_EQ(q.verdict, FoldVerdict::fold_free) << order;
    EXPECT_EQ(q.quick_cells, q.cells) << "an affine map passes the quick test everywhere";
    FoldCertificateOptions exact;
    exact.quick_test = false;
    const FoldCertificate c = certify_fold_free(F, exact);
    EXPECT_EQ(c.verdict, FoldVerdict::fold_free) << order;
    EXPECT_EQ(c.quick_cells, 0u);
    EXPECT_GT(c.min_det_coefficient, 0.0);
    EXPECT_EQ(c.cells, std::size_t(4 * 3 * 5)) << "one Bézier cell per knot span";
    EXPECT_EQ(c.boxes, c.cells) << "an affine map needs no subdivision";
    EXPECT_TRUE(c.fold_cells.empty());
  }
}

TEST(FoldCertificate, FindsAPlantedFoldWhereDetJIsNonPositive) {
  auto F = identity_lattice(glm::ivec3(4), glm::ivec3(6));
  // Push the plane of controls i = 2 past the planes i = 3 and 4 along u: the map reverses between them.
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j) F.control_point(2, j, k).x = 1.0;
  const FoldCertificate c = certify_fold_free(F);
  ASSERT_EQ(c.verdict, FoldVerdict::fold);
  ASSERT_FALSE(c.fold_params.empty());
  for (std::size_t i = 0; i < c.fold_params.size(); ++i) {
    EXPECT_LE(jacobian_determinant(F, c.fold_params[i]), 1e-9) << "the reported point folds";
    EXPECT_NEAR(c.fold_det[i], jacobian_determinant(F, c.fold_params[i]), 1e-6);
    EXPECT_LT(glm::length(c.fold_points[i] - F.eval(c.fold_params[i])), 1e-12);
  }
  EXPECT_LT(sampled_min_det(F, 24), 0.0) << "the plant really folds";
}

TEST(FoldCertificate, NeverCertifiesWhatSamplingFindsFolded) {
  std::mt19937 rng(11);
  int certified = 0, folds = 0, undecided = 0, sampled_folds = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const int order = 2 + trial % 3;
    auto F = identity_lattice(glm::ivec3(order), glm::ivec3(order + 1 + trial % 3));
    // Perturbations from gentle to violent: some lattices fold, some do not.
    std::normal_distribution<double> noise(0.0, 0.02 + 0.2 * (trial % 8) / 7.0);
    for (glm::dvec3& p : F.control_points()) p += glm::dvec3(noise(rng), noise(rng), noise(rng));
    const FoldCertificate c = certify_fold_free(F);
    const double sampled = sampled_min_det(F, 12);
    if (sampled <= 0.0) {
      ++sampled_folds;
      EXPECT_NE(c.verdict, FoldVerdict::fold_free) << "trial " << trial << ": certified, yet det J = " << sampled;
    }
    if (c.verdict == FoldVerdict::fold) {
      ++folds;
      for (const glm::dvec3& t : c.fold_params) EXPECT_LE(jacobian_determinant(F, t), 1e-9) << "trial " << trial;
    }
    certified += c.verdict == FoldVerdict::fold_free;
    undecided += c.verdict == FoldVerdict::undecided;
  }
  // The sample is varied enough to exercise all outcomes.
  EXPECT_GT(certified, 40);
  EXPECT_GT(folds, 40);
  EXPECT_GT(sampled_folds, 40);
  EXPECT_LT(undecided, 24);
}

TEST(FoldCertificate, QuickTestOnlyShortensTheWay) {
  // The quick test (first-difference boxes, Gershgorin) decides gently deformed cells and never changes a verdict;
  // on rotated and sheared lattices too (it is preconditioned by each cell's own mean Jacobian).
  std::mt19937 rng(29);
  std::size_t quick = 0, cells = 0;
  int compared = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int order = 2 + trial % 3;
    auto F = identity_lattice(glm::ivec3(order), glm::ivec3(order + 2 + trial % 2));
    const glm::dmat3 A = glm::dmat3(1.0, 0.4, -0.2, -0.3, 0.8, 0.5, 0.1, -0.6, 1.2) * (0.5 + trial % 5);
    std::normal_distribution<double> noise(0.0, 0.01 + 0.12 * (trial % 6) / 5.0);
    for (glm::dvec3& p : F.control_points()) p = A * p + glm::dvec3(noise(rng), noise(rng), noise(rng));
    FoldCertificateOptions exact;
    exact.quick_test = false;
    const FoldCertificate with = certify_fold_free(F), without = certify_fold_free(F, exact);
    quick += with.quick_cells;
    cells += with.cells;
    if (without.verdict == FoldVerdict::undecided) continue;
    ++compared;
    EXPECT_EQ(with.verdict, without.verdict) << "trial " << trial;
    EXPECT_EQ(with.fold_cells, without.fold_cells) << "trial " << trial;
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(quick, cells / 4) << "the quick test decides a good share of the cells";
  EXPECT_LT(quick, cells) << "and not all of them (some lattices fold)";
  RecordProperty("quick_share", std::to_string(double(quick) / double(cells)));
}

TEST(FoldCertificate, PeriodicAxesAreUnwrapped) {
  // A closed ring: u periodic around y, v radial, w along y. Its orientation is fixed by construction.
  const int period = 8;
  const KnotVector ku = KnotVector::periodic_uniform(4, period), kv = KnotVector::clamped_uniform(2, 2),
                   kw = KnotVector::clamped_uniform(2, 2);
  std::vector<glm::dvec3> P;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < period; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * i / period, r = 2.0 + j;
        P.emplace_back(r * std::cos(a), k, -r * std::sin(a));
      }
  TrivariateBSpline<glm::dvec3> F(ku, kv, kw, P);
  const double sampled = sampled_min_det(F, 16);
  const FoldCertificate c = certify_fold_free(F);
  EXPECT_EQ(c.cells, std::size_t(period));
  EXPECT_EQ(c.verdict, sampled > 0.0 ? FoldVerdict::fold_free : FoldVerdict::fold) << "sampled min " << sampled;
  // Mirrored (every point reflected in x): turned inside out everywhere.
  for (glm::dvec3& p : P) p.x = -p.x;
  const FoldCertificate m = certify_fold_free(TrivariateBSpline<glm::dvec3>(ku, kv, kw, P));
  EXPECT_NE(m.verdict, c.verdict);
}

TEST(FoldCertificate, RefusesWhatItCannotJudge) {
  const auto F = identity_lattice(glm::ivec3(3), glm::ivec3(4));
  FoldCertificateOptions o;
  o.max_depth = 13;
  EXPECT_THROW(certify_fold_free(F, o), std::invalid_argument);
  auto G = F;
  G.control_point(1, 1, 1).y = NAN;
  EXPECT_THROW(certify_fold_free(G), std::invalid_argument);
  const KnotVector k1 = KnotVector::clamped_uniform(1, 3), k3 = KnotVector::clamped_uniform(3, 3);
  std::vector<glm::dvec3> P(27, glm::dvec3(0.0));
  EXPECT_THROW(certify_fold_free(TrivariateBSpline<glm::dvec3>(k1, k3, k3, P)), std::invalid_argument);
}

// x(u) = (u − 1/3)³ along u (Bernstein controls −1/27, 2/27, −4/27, 8/27), identity along v and w: det J = 3(u − 1/3)²
// ≥ 0, zero on the plane u = 1/3, which no dyadic split reaches. Every box across that plane stays mixed, so each
// level of subdivision judges 4× more boxes (2^d × 2^d across the plane).
TrivariateBSpline<glm::dvec3> tangent_lattice() {
  const KnotVector ku = KnotVector::clamped_uniform(4, 4), kl = KnotVector::clamped_uniform(2, 2);
  const double xu[4] = {-1.0 / 27, 2.0 / 27, -4.0 / 27, 8.0 / 27};
  std::vector<glm::dvec3> P;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) P.emplace_back(xu[i], j, k);
  return TrivariateBSpline<glm::dvec3>(ku, kl, kl, std::move(P));
}

TEST(FoldCertificate, TheBoxBudgetBoundsATangentLattice) {
  const auto F = tangent_lattice();
  EXPECT_NEAR(jacobian_determinant(F, glm::dvec3(1.0 / 3, 0.5, 0.5)), 0.0, 1e-12);
  EXPECT_GT(sampled_min_det(F, 24), 0.0) << "tangent, not folded";
  FoldCertificateOptions o;
  o.max_depth = 4;
  const FoldCertificate shallow = certify_fold_free(F, o);
  EXPECT_EQ(shallow.verdict, FoldVerdict::undecided);
  EXPECT_EQ(shallow.budget_cells, 0u) << "depth 4 is within the default budget";
  EXPECT_GE(shallow.boxes, std::size_t(1 + 8 + 4 * 8 + 16 * 8 + 64 * 8) / 2) << "the boxes grow by 4 a level";
  // Depth 12 would judge ~4^12 = 16.7 M boxes; the budget stops the cell at its share and calls it undecided.
  o.max_depth = 12;
  o.max_boxes = 20000;
  const FoldCertificate deep = certify_fold_free(F, o);
  EXPECT_EQ(deep.verdict, FoldVerdict::undecided);
  EXPECT_EQ(deep.budget_cells, 1u);
  EXPECT_LE(deep.boxes, o.max_boxes);
  EXPECT_EQ(deep.boxes, o.max_boxes) << "the whole share was spent";
  // The same budget on the same lattice gives the same boxes (deterministic, per cell).
  EXPECT_EQ(certify_fold_free(F, o).boxes, deep.boxes);
  o.max_boxes = 0;
  EXPECT_THROW(certify_fold_free(F, o), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
