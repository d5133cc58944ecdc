// trispline::core silhouettes of an iso-surface D = c of a VolumeSpline (seed §7.3.3, Eq. 7.2).
//
// A silhouette point x satisfies D(x) = c and G(x)·V(x) = 0 with G = ∇D and V the view direction: constant for an
// orthographic view, x − eye for a perspective one; the points form curves (the contour generator) with tangent
// ∇D × ∇(G·V). Candidates come from the singleton table (singletons.h): the singletons whose value range holds c and
// whose gradient cone holds a direction orthogonal to V. A candidate whose Bézier hull of G·V holds 0 is split into
// `subdivision`³ sub-cells (de Casteljau on its Bézier form); each sub-cell whose value range still holds c and whose
// range of G·V still holds 0 seeds a multivariate Newton–Raphson solve of Eq. 7.2 (minimum-norm steps for 2 equations
// in 3 unknowns) from its centre. Beyond the seed, which strokes the converged points one by one, each new point
// starts a predictor–corrector trace of its curve both ways (tangent step, then Newton back onto the curve; every
// traced point is converged to the same accuracy), and the cells a trace crosses seed nothing more. The volume is
// traced in blocks of 32³ cells in parallel; a trace ends on a block face at the exact crossing of the curve with the
// face plane, where the neighbour block's trace of the same curve ends too, and the pieces are joined there. Each
// point knows whether the iso-surface hides it from the eye.
//
// A view with a pixel size limits the density to what the screen shows: where a cell covers fewer than
// SilhouetteParams::pixel_step pixels, the trace takes steps of up to a cell that turn by up to 60° (half a cell and
// 25° otherwise), and points closer than a pixel on screen to the last one kept are merged. SilhouetteSequence serves
// a run of nearby views (an orbit): it files the cells holding the level once, and seeds each view from the previous
// view's curves before the table (Burns et al. 2005, seed-and-traverse).
#pragma once

#include <atomic>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/volume/singletons.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

// The view a silhouette is taken for, in world units (millimetres).
struct SilhouetteView {
  bool perspective = true;
  glm::dvec3 eye{0.0};                   // perspective: the eye position
  glm::dvec3 direction{0.0, 0.0, -1.0};  // orthographic: the viewing direction (need not be unit)
  // The size of a pixel, millimetres: perspective, at unit distance from the eye (2·tan(fov/2) ÷ viewport height);
  // orthographic, anywhere (view height ÷ viewport height). 0: not on a screen — no density limit (exports).
  double pixel_size = 0.0;
};

// The seed's two operational parameters (§7.3.3) and the hidden-line mode.
struct SilhouetteParams {
  // Sub-cells per singleton axis that seed Newton (1 = the singleton's centre only; 1…4). Tracing gives the curves
  // their density, so more seeds only find more of the curves that lie wholly inside one singleton.
  int subdivision = 1;
  // Newton stops when |D − c| ≤ accuracy·range(D) and |Ĝ·V̂| ≤ accuracy (dimensionless, 1e-12…1e-2).
  double accuracy = 1e-7;
  // Test every point for occlusion by the iso-surface (SilhouettePolyline::visible); false leaves every point visible.
  bool hidden_test = true;
  // false: cells the iso-surface hides from the eye seed nothing, for views that drop hidden parts (the editor with
  // Hidden lines "remove"). A curve is then traced only when some cell of it may be seen; once seeded it is traced
  // whole and tested as usual. Hidden means: the cell's nearest point lies more than 4 index units beyond the
  // farthest first crossing of D = iso over the rays of a coarse 128 × 128 map from the eye around its footprint —
  // conservative but for openings narrower than the map's spacing (about 1/128 of the volume's extent on screen).
  // With the eye inside the grid box every cell seeds.
  bool seed_hidden = true;
  // Screen density, pixels (views with SilhouetteView::pixel_size; 0 = off, up to 16): where a cell covers fewer
  // than this many pixels the trace takes coarser steps, and points closer than a pixel on screen are merged.
  double pixel_step = 2.0;
};

// One connected piece of silhouette, world units. The arrays have one entry per point.
struct SilhouettePolyline {
  std::vector<glm::dvec3> points;      // #P × 3, millimetres (world)
  std::vector<float> gradient_norm;    // #P, |∇D| per millimetre (the seed's stroke styles shade by it)
  std::vector<unsigned char> visible;  // #P, 1 = seen from the eye, 0 = hidden behind the iso-surface
  bool closed = false;                 // the last point joins the first
};

struct SilhouetteResult {
  std::vector<SilhouettePolyline> polylines;
  // Figures of this extraction.
  std::size_t candidates = 0;            // singletons that passed the range and cone tests
  std::size_t seeds = 0;                 // sub-cells that seeded Newton (traced cells seed nothing)
  std::size_t points = 0;                // converged points kept (= Σ polyline sizes)
  std::size_t hidden_cells = 0;          // cells holding the level that seeded nothing as hidden (seed_hidden false)
  std::size_t traced_from_previous = 0;  // traces started from the previous view's curves (SilhouetteSequence)
  double max_value_residual = 0.0;       // max |D − c| / range(D) over the points
  double max_dot_residual = 0.0;         // max |Ĝ·V̂| over the points (world-space unit vectors)
  double length_mm = 0.0;                // total polyline length, millimetres
  double extract_ms = 0.0;               // wall-clock: candidates + seeds + tracing + joining
  double hidden_ms = 0.0;                // wall-clock: the occlusion test
};

// Silhouette of D = `iso` (the volume's units) for `view`. `table` must have been built from `spline`
// (build_singleton_table). Throws std::invalid_argument: non-finite iso or view, perspective eye == a degenerate
// point, parameters out of range. Deterministic: the same inputs give the same polylines bit for bit (threads
// write to disjoint slots, results are ordered by cell).
SilhouetteResult extract_silhouettes(const VolumeSpline& spline, const SingletonTable& table, double iso,
                                     const SilhouetteView& view, const SilhouetteParams& params = {});

// Silhouettes of one volume over a run of nearby views (the editor's orbit; `bench silhouettes --orbit`). The cells
// whose value range holds the level are filed by block once per level; each view then traces first from the previous
// view's curves — a point every 2 index units, Newton for the new view from it (Burns et al. 2005) — and falls back
// to the table for the curves the previous view did not have (every candidate cell no trace has crossed). The result
// for a view depends on the views before it (which curves are traced first decides where joined pieces begin), so
// exports and replays use extract_silhouettes. Holds the spline and table alive; not thread-safe (one view at a time).
class SilhouetteSequence {
 public:
  SilhouetteSequence(std::shared_ptr<const VolumeSpline> spline, std::shared_ptr<const SingletonTable> table);
  ~SilhouetteSequence();
  SilhouetteSequence(const SilhouetteSequence&) = delete;
  SilhouetteSequence& operator=(const SilhouetteSequence&) = delete;

  // As extract_silhouettes for the next view. Throws as it does; a throw leaves the sequence as it was.
  SilhouetteResult next(double iso, const SilhouetteView& view, const SilhouetteParams& params = {});
  // Forget the previous view (the next one seeds from the table alone).
  void restart();
  const VolumeSpline& spline() const { return *spline_; }
  const SingletonTable& table() const { return *table_; }

 private:
  struct Filed;
  std::shared_ptr<const VolumeSpline> spline_;
  std::shared_ptr<const SingletonTable> table_;
  std::unique_ptr<Filed> filed_;      // the cells holding the last view's level, by block
  std::vector<glm::dvec3> previous_;  // index space: the previous view's curves, a point every 2 index units
};

// Whether the segment from index-space point `from` towards the eye (perspective: to `view.eye`; orthographic:
// against `view.direction` to the volume's boundary) crosses D = iso, ignoring the first `skip` index units (the
// point's own neighbourhood). Uses the table's macro-cells to skip space that cannot hold the level.
bool iso_occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const SilhouetteView& view,
                  const glm::dvec3& from_index, double skip = 1.5);

}  // namespace trispline::core
