// Pressing a lattice with a swept sphere. See pressing.h. Source: seed §2.4.1 (Fig. 2.7, 2.8; Eq. 2.3, 2.4).
#include "core/placement/pressing.h"

#include "core/ffd/fold_certificate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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
        for (const glm::dvec3& centre : path) w = std::max(w, falloff_weight(falloff, glm::length(p - centre) / radius));
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
                                (start.verdict == FoldVerdict::fold ? "it folds in " + std::to_string(start.fold_cells.size()) + " cells"
                                                                    : "undecided in " + std::to_string(start.undecided_cells.size()) + " cells") +
                                "): there is nothing to keep");
  auto attempt = [&](double s, FoldFreePress& into) {
    PressResult r;
    TrivariateBSpline<glm::dvec3> after = press_lattice(before, path, radius, s, falloff, &r);
    ++out.certificates;
    if (certify_fold_free(after, options).verdict != FoldVerdict::fold_free) return false;
    into.lattice = std::move(after);
    into.strength = s;
    into.result = r;
    return true;
  };
  if (attempt(strength, out)) return out;
  out.limited = true;
  double lo = 0.0, hi = 1.0;  // fractions of the strength: lo certified (0 = the lattice before), hi not
  for (int step = 0; step < 10; ++step) {
    const double mid = 0.5 * (lo + hi);
    if (attempt(mid * strength, out)) lo = mid;
    else hi = mid;
  }
  if (lo == 0.0) out.lattice = before, out.strength = 0.0, out.result = {};
  return out;
}

}  // namespace trispline::core
