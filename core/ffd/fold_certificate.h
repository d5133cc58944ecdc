// trispline::core fold-free certificate of an FFD: is det J of the trivariate map F positive on its whole domain?
//
// A lattice folds where det J ≤ 0 (the deformed object turns inside out there); sampling det J can only ever find a
// fold, never rule one out. On each Bézier cell of F (knot insertion at every interior knot, P&T A5.3), with degrees
// (p, q, r), the partial derivatives are Bézier polynomials of degrees (p−1, q, r), (p, q−1, r), (p, q, r−1), so
//   det J = ∂F/∂u · (∂F/∂v × ∂F/∂w)
// is one Bernstein polynomial of degree (3p−1, 3q−1, 3r−1) (729 coefficients for a tri-cubic cell), computed exactly
// by products of Bernstein forms (scaled coefficients multiply by convolution; Farouki & Rajan 1988). Its
// coefficients bound it (convex hull property) and its corner coefficients are its values at the cell's corners. So:
//   the quick test passes                          → certified fold-free without the Bernstein form (the columns of J,
//                                                    boxed from first differences, preconditioned by the inverse of
//                                                    their centre, are diagonally dominant: Gershgorin);
//   every coefficient > 0                          → the cell is certified fold-free;
//   a corner value ≤ 0                             → a fold, at that corner;
//   otherwise the cell is split in halves (de Casteljau, all three axes) and its eight children are judged the same
//   way, down to `max_depth` splits; a box still mixed there is undecided.
// This is the validity check of high-order finite elements (Johnen, Remacle & Geuzaine 2013) applied to FFD lattices;
// the seed (§2.6) names injectivity as future work. Units: parameters in F's knot domain (an FFD's is [0,1]³), points
// in the control points' space. Deterministic; cells are judged in parallel and reported in cell order.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

enum class FoldVerdict { fold_free, fold, undecided };
const char* fold_verdict_name(FoldVerdict v);  // "fold_free", "fold", "undecided"

struct FoldCertificateOptions {
  // Halvings of a cell (per axis, all three at once) before a mixed box is called undecided (0…12).
  int max_depth = 6;
  // Try the quick sufficient test (first differences, Gershgorin) before the exact Bernstein form.
  bool quick_test = true;
  // The work budget: Bernstein boxes judged in all. Every cell first gets its quick test and its whole-cell box; the
  // cells still mixed then share what is left evenly (at least 1 each). A box tangent to det J = 0 splits into 4^d
  // boxes at depth d, so without it max_depth 12 on one tangent cell is 16.7 M boxes (minutes); a cell that spends its
  // share is undecided. The share is per cell, so the verdicts do not depend on the thread count. 512 K tri-cubic boxes
  // (729 coefficients, ~11 µs each on one core of the machine in docs/performance.md) take ~6 s on one core.
  std::size_t max_boxes = std::size_t(1) << 19;
};

struct FoldCertificate {
  FoldVerdict verdict = FoldVerdict::fold_free;  // fold if any cell folds, else undecided if any is, else fold_free
  // One entry per folding cell, in cell order (u fastest): the cell (its knot spans' index per axis), a parameter
  // point in it with det J ≤ 0, F there and det J there (per unit of the parameters).
  std::vector<glm::ivec3> fold_cells;
  std::vector<glm::dvec3> fold_params;
  std::vector<glm::dvec3> fold_points;
  std::vector<double> fold_det;
  std::vector<glm::ivec3> undecided_cells;  // cells with a box still mixed at max_depth or when their share ran out
  std::size_t budget_cells = 0;             // undecided cells among them that spent their share of max_boxes
  std::size_t cells = 0;                    // Bézier cells judged
  std::size_t quick_cells = 0;              // cells certified by the quick test alone
  std::size_t boxes = 0;                    // Bernstein boxes judged (cells plus their sub-boxes)
  double min_det_coefficient = 0.0;         // smallest Bernstein coefficient of det J over the cells the Bernstein
                                            // test judged (unsplit); 0 when the quick test decided every cell
};

// Judges F (orders ≥ 2 per axis; periodic axes are unwrapped to their period). Throws std::invalid_argument: an order
// below 2, max_depth outside 0…12, max_boxes 0, non-finite control points.
FoldCertificate certify_fold_free(const TrivariateBSpline<glm::dvec3>& F, const FoldCertificateOptions& options = {});

}  // namespace trispline::core
