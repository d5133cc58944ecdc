// `dffd.split` — a global discontinuous FFD that splits an object around obstacles and re-forms it behind them
// (seed §6.3.1–6.3.2, Fig. 6.1, 6.4, 6.7, 6.10, 6.11). Fields: declared in dffd_split.cpp (ParamSchema), listed in
// docs/commands.md; the lattice box defaults to the obstacles grown by margin along axis and to contain the object
// across.
// `axis` is the direction the object travels through the obstacles (the lattice's u), `w_axis` the lattice's w (the
// slicing planes W_k are orthogonal to it; for vertical bars it is their length axis). The construction is
// core::build_global_dffd (dffd_global.h); the object keeps its rest mesh and gets a DffdRig, evaluated (split,
// capped, deformed) at every scene time, so animating its parameter offset along u (anim.keyframe) walks it through
// the obstacles. Running it again on a split object replaces its rig. Undo restores the object bit for bit.
// Clearance: no vertex may stay inside an obstacle (ObstacleInterior, CGAL). Where the construction leaves some
// (its rows fit the cross-section only at their own v and w), the split refines in up to 4 rounds: controls in v and
// w doubled, clearance raised by 1.5× the deepest one's depth, κ widened 1.5× when a round folds. A seam's other
// state (cap ↔ stitch) is cleared too while that helps, and reported. The log line keeps the user's values (a replay
// refines the same way).
// report.json: discontinuities, v_knots, projected_points, max_displacement, fold_overs, w_s, cut_edges, cap_loops,
// open_chains, cap_triangles (untextured), textured_cap_triangles (with an inside texture: the caps refined for it),
// outside_vertices, vertices_before, vertices_after (of the world mesh, textured caps included), inside_obstacle (0),
// inside_obstacle_other_state (null without a seam), inside_before_refinement, refinement_rounds, clearance_used,
// controls_used, kernel_width_used, unchecked_obstacles (obstacles that bound no volume: open or non-manifold meshes,
// not checked), build_ms, eval_ms.
// Errors (CommandError, field named): unknown object, an FFD or clip object ("object"); unknown / repeated /
// self / empty obstacle ("obstacles"); axes equal ("w_axis"); order / controls out of range; kernel_width ≤ 0 or
// a fold-over with fold = reject ("kernel_width": count, first (i,j,k), world position); obstacle larger than the
// given box ("box"); caps asked for a mesh that is not closed at a cut ("openings"); vertices still inside an
// obstacle after the refinements, or a refinement that fails ("clearance": how many, how deep, what was tried).
#pragma once

#include <optional>
#include <vector>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/dffd/dffd_global.h"

namespace trispline::core {

struct DffdSplitParams {
  std::string object;
  std::vector<std::string> obstacles;  // ids of other objects (their meshes when the command runs)
  GlobalDffdParams dffd;               // kernel_width is required in a line
};

// The fields of dffd.split that configure the lattice (axis, w_axis, order, controls, kernel, …).
const ParamSchema<GlobalDffdParams>& global_dffd_schema();

struct DffdSplitCommand : ObjectSnapshotCommand<DffdSplitCommand, DffdSplitParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
