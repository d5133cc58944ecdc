// trispline::core guarantees benchmark — the figures behind `trispline bench bounds` (docs/performance.md).
//
// The fold-free certificate (core/ffd/fold_certificate.h): milliseconds to judge lattices of 4³, 8³ and 16³ control
// points, tri-quadratic and tri-cubic, each an identity lattice with a mild random displacement (fold-free: every
// cell is judged in full), best of `repeats`; then a soundness sweep: `lattices` random lattices (orders 2–4, 3–6
// controls per axis, displacements from gentle to violent) judged and sampled densely (det J on a 12³ grid), counting
// verdicts and the lattices certified fold-free although a sample has det J ≤ 0 (must be 0) and the folds reported at
// points where det J > 0 (must be 0); then the per-triangle deformation-error bounds (core/ffd/deformation_bounds.h) of
// every triangle of the FFD benchmark's mesh (the bunny refined to 836K vertices) in a perturbed tri-cubic 8³ lattice;
// then their soundness: `soundness_triangles` triangles of the bunny (as loaded) in random lattices, each bound
// (right triangle, circumcircle, enclosing circle, best, normal-projected) against the error measured by sampling and
// Newton, counting bounds exceeded (must be 0) and the tightness (bound ÷ measured, median and worst); then the
// certified refinement of the seed's cube (midpoint / Greville / best split) beside the seed's counts.
// Prints figures; never asserts timings.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace trispline::core {

struct BoundsBenchOptions {
  int repeats = 5;                                  // ≥ 1: timings are the best of these
  int lattices = 1000;                              // ≥ 0: random lattices in the soundness sweep
  std::string mesh_path = "assets/data/bunny.obj";  // the per-triangle bounds' mesh (a sphere when absent)
  int subdivision_level = 2;                        // its bilinear refinement level
  int soundness_triangles = 1'000'000;              // ≥ 0: triangles of the unrefined mesh checked in random lattices
};

// Result: {bench:"bounds", threads, certificate:[{order, controls, cells, boxes, quick_cells, verdict, ms, exact_boxes,
//          exact_verdict, exact_ms}] (exact_*: without the quick test), sweep:{lattices,
//          fold_free, fold, undecided, sampled_folds, certified_but_sampled_fold, fold_reported_at_positive_det},
//          triangles:{mesh, vertices, triangles, prepare_ms, ms, per_second, max_bound, median_bound},
//          soundness:{mesh, triangles, lattices, unbounded, ms, methods:{NAME:{exceeded, tightness:{count, median,
//          worst}}}}, refinement:[{deformation, tolerance, midpoint|greville|best:{triangles, max_bound, stopped_by,
//          ms}, best_over_midpoint}], refinement_seed:{midpoint, greville, note}}.
// Throws std::invalid_argument on bad options.
nlohmann::json run_bounds_benchmark(const BoundsBenchOptions& options);

}  // namespace trispline::core
