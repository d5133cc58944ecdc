// The spherical pressing tool's math on a placed object's control lattice (seed §2.4.1, Fig. 2.7, 2.8): the
// lattice after a sphere swept along a path, and the column direction V_P both pressing and pulling move along.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/ffd/falloff.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// What one press did (lattice.press's stats).
struct PressResult {
  int moved = 0;                // control points moved
  double max_displacement = 0;  // world units
};

// The lattice after one sphere sweep: a control point P_ijk moves by −strength·w·V_P, w = max over the path of
// falloff(|P_ijk − c| / radius), so it moves once by the strongest weight the swept sphere gave it; points outside
// every sphere stay. `path` #P × 3 sphere centres, world units (≥ 1 point); radius > 0 and strength in world units
// (> 0 presses into the volume, < 0 pulls). Positions before the sweep decide weights and directions. The editor's
// Press tool calls it for the live preview during a drag, so the preview is exactly what the command at mouse-up
// produces. Throws std::invalid_argument for a column of zero length (no V_P). Source: seed §2.4.1, Fig. 2.7.
TrivariateBSpline<glm::dvec3> press_lattice(const TrivariateBSpline<glm::dvec3>& before,
                                            const std::vector<glm::dvec3>& path, double radius, double strength,
                                            Falloff falloff, PressResult* result = nullptr);

// A press limited so that the lattice stays certified fold-free (fold_certificate.h): the Press tool's "Keep
// fold-free" and lattice.press's keep_fold_free.
struct FoldFreePress {
  TrivariateBSpline<glm::dvec3> lattice;  // the pressed lattice, certified fold-free
  double strength = 0;                    // the strength used, world units (same sign as asked, |.| ≤ |asked|)
  bool limited = false;                   // less than asked
  int certificates = 0;                   // certificates computed
  PressResult result;
};

// Below this fraction of the asked strength a limited press changes nothing visible: refused instead.
inline constexpr double kMinMovableFraction = 1.0 / 64.0;

// press_lattice with the largest strength s (same sign, |s| ≤ |strength|) found by bisection whose result is
// certified fold-free: the whole strength when that is certified, else 10 halvings of [0, |strength|] keeping the
// largest certified one (certificates are exact: whatever is returned is certified, even where the verdict is not
// monotone in s; an undecided verdict is asked again 3 halvings deeper, max 12). Throws std::invalid_argument when
// `before` itself is not certified fold-free (the message says whether it folds or is undecided), when less than
// kMinMovableFraction of the strength can be certified ("the lattice cannot move this way", with the cell that folds
// or stays undecided: a lattice left at the edge of folding by an earlier limited press), and as press_lattice does.
FoldFreePress press_lattice_fold_free(const TrivariateBSpline<glm::dvec3>& before, const std::vector<glm::dvec3>& path,
                                      double radius, double strength, Falloff falloff, int max_depth = 6);

// Unit column direction V_P of column (i, j) of `lattice` (top minus contact control point); for a zero-length
// column the mean direction of all columns. Throws std::invalid_argument if that is zero too or (i, j) is outside.
glm::dvec3 column_direction(const TrivariateBSpline<glm::dvec3>& lattice, int i, int j);

}  // namespace trispline::core
