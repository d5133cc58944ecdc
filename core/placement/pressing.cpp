// Pressing a lattice with a swept sphere. See pressing.h. Source: seed §2.4.1 (Fig. 2.7, 2.8; Eq. 2.3, 2.4).
#include "core/placement/pressing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/ffd/fold_certificate.h"

namespace trispline::core {
namespace {

glm::dvec3 raw_column(const TrivariateBSpline<glm::dvec3>& F, int i, int j) {
  const int n = F.control_counts().z;
  return F.control_point(i, j, n - 1) - F.control_point(i, j, 0);
}

}  // namespace

glm::dvec3 column_direction(const TrivariateBSpline<glm::dvec3>& F, int i, int j) {
  const glm::ivec3 c = F.control_counts();
  if (i < 0 || j < 0 || i >= c.x || j >= c.y)
    throw std::invalid_argument("column (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " +
                                std::to_string(c.x) + " x " + std::to_string(c.y) + " columns of the lattice");
  glm::dvec3 d = raw_column(F, i, j);
  if (glm::length(d) > 0.0) return glm::normalize(d);
  d = glm::dvec3(0.0);
  for (int jj = 0; jj < c.y; ++jj)
    for (int ii = 0; ii < c.x; ++ii) {
      const glm::dvec3 e = raw_column(F, ii, jj);
      if (glm::length(e) > 0.0) d += glm::normalize(e);
    }
  if (!(glm::length(d) > 0.0)) throw std::invalid_argument("the lattice's columns have zero length");
  return glm::normalize(d);
}

TrivariateBSpline<glm::dvec3> press_lattice(const TrivariateBSpline<glm::dvec3>& before,
                                            const std::vector<glm::dvec3>& path, double radius, double strength,
                                            Falloff falloff, PressResult* result) {
  TrivariateBSpline<glm::dvec3> after = before;
  const glm::ivec3 c = before.control_counts();
  PressResult r;
  for (int j = 0; j < c.y; ++j)
    for (int i = 0; i < c.x; ++i) {
      const glm::dvec3 vp = column_direction(before, i, j);
      for (int k = 0; k < c.z; ++k) {
        const glm::dvec3& p = before.control_point(i, j, k);
        double w = 0.0;
        for (const glm::dvec3& centre : path)
          w = std::max(w, falloff_weight(falloff, glm::length(p - centre) / radius));
        if (w <= 0.0) continue;
        after.control_point(i, j, k) = p - strength * w * vp;
        ++r.moved;
        r.max_displacement = std::max(r.max_displacement, std::abs(strength) * w);
      }
    }
  if (result) *result = r;
  return after;
}

FoldFreePress press_lattice_fold_free(const TrivariateBSpline<glm::dvec3>& before, const std::vector<glm::dvec3>& path,
                                      double radius, double strength, Falloff falloff, int max_depth) {
  FoldCertificateOptions options;
  options.max_depth = max_depth;
  FoldFreePress out{before, 0.0, false, 0, {}};
  const FoldCertificate start = certify_fold_free(before, options);
  ++out.certificates;
  if (start.verdict != FoldVerdict::fold_free)
    throw std::invalid_argument(std::string("the lattice is not certified fold-free before the press (") +
                                (start.verdict == FoldVerdict::fold
                                     ? "it folds in " + std::to_string(start.fold_cells.size()) + " cells"
                                     : "undecided in " + std::to_string(start.undecided_cells.size()) + " cells") +
                                "): there is nothing to keep");
  // A verdict left undecided at max_depth (det J touching 0 inside a box, as it does right after a limited press) is
  // asked again 3 halvings deeper before the strength counts as uncertified.
  FoldCertificateOptions deeper = options;
  deeper.max_depth = std::min(12, max_depth + 3);
  FoldCertificate refused;  // the certificate of the smallest strength that was not certified
  double refused_at = 1.0;
  auto attempt = [&](double fraction, FoldFreePress& into) {
    PressResult r;
    TrivariateBSpline<glm::dvec3> after = press_lattice(before, path, radius, fraction * strength, falloff, &r);
    ++out.certificates;
    FoldCertificate c = certify_fold_free(after, options);
    if (c.verdict == FoldVerdict::undecided && deeper.max_depth > options.max_depth) {
      ++out.certificates;
      c = certify_fold_free(after, deeper);
    }
    if (c.verdict != FoldVerdict::fold_free) {
      if (fraction <= refused_at) refused = std::move(c), refused_at = fraction;
      return false;
    }
    into.lattice = std::move(after);
    into.strength = fraction * strength;
    into.result = r;
    return true;
  };
  if (attempt(1.0, out)) return out;
  out.limited = true;
  double lo = 0.0, hi = 1.0;  // fractions of the strength: lo certified (0 = the lattice before), hi not
  for (int step = 0; step < 10; ++step) {
    const double mid = 0.5 * (lo + hi);
    if (attempt(mid, out))
      lo = mid;
    else
      hi = mid;
  }
  // Less than kMinMovableFraction of the strength is no visible change: the lattice cannot move this way.
  if (lo < kMinMovableFraction) {
    const bool folds = refused.verdict == FoldVerdict::fold;
    std::string where;
    const std::vector<glm::ivec3>& cells = folds ? refused.fold_cells : refused.undecided_cells;
    if (!cells.empty())
      where = " in cell (" + std::to_string(cells[0].x) + "," + std::to_string(cells[0].y) + "," +
              std::to_string(cells[0].z) + ")";
    char amount[64];
    std::snprintf(amount, sizeof amount, "%.3g", std::abs(refused_at * strength));
    throw std::invalid_argument(std::string("the lattice cannot move this way and stay certified fold-free: a ") +
                                (strength < 0 ? "pull" : "press") + " of " + amount + " already " +
                                (folds ? "folds it" : "cannot be certified") + where +
                                " (it is at the edge of folding there); press elsewhere, with a larger radius or a "
                                "smooth falloff, or without Keep fold-free");
  }
  return out;
}

}  // namespace trispline::core
