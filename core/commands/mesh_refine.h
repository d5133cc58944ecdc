// `mesh.refine` — adaptive refinement of a deformed object's rest mesh so that its deformed edges follow the FFD
// (seed §2.4.2, Eq. 2.6, Fig. 2.9–2.10; core/ffd/refine.h has the algorithm).
//   {"cmd":"mesh.refine","object":"ID","tolerance":t,"criterion":"midpoint|greville","max_iterations":n,
//    "max_triangles":m}
// tolerance: world units (> 0, finite); criterion: "greville" (default; the seed's split at the nodal value of the
// farthest control point of the composed curve, tolerance on that control point's distance from the chord) or
// "midpoint" (Chua & Neumann, Eq. 2.6); max_iterations: split rounds (default 16, 0..64); max_triangles: a round
// that would exceed it is not applied (default 2,000,000, ≥ the object's triangle count, ≤ 8,000,000).
// The refinement runs in the object's space (rest_mesh) with the binding's parameters: the object's transform and the
// embedding are affine, so splitting an edge at t in object space is the same point as in world rest space; the
// object keeps its transform, lattice and embedding and gets a new binding with the interpolated parameters. Splits
// account for the object's param_offset (the shown pose). Undo restores the object as it was.
// Errors (CommandError, field named): unknown object / object without an FFD ("object"), tolerance ≤ 0 or not
// finite or below kMinRefineTolerance × the object's size ("tolerance"), unknown criterion ("criterion"), limits out of
// range ("max_iterations", "max_triangles").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/ffd/refine.h"

namespace trispline::core {

// The smallest tolerance mesh.refine accepts, relative to the deformed object's world size (bounding-box diagonal):
// float32's resolution, what scene.glb stores.
inline constexpr double kMinRefineTolerance = 1e-7;

struct MeshRefineParams {
  std::string object;
  double tolerance = 0.01;                 // world units
  std::string criterion = "greville";      // midpoint (Eq. 2.6) | greville
  std::string error = "edge";              // edge: each edge's measure | bound: each triangle's certified bound
  int max_iterations = 16;                 // split rounds
  std::int64_t max_triangles = 2'000'000;  // the memory budget of a refinement
};

class MeshRefineCommand : public ObjectSnapshotCommand<MeshRefineCommand, MeshRefineParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<MeshRefineParams>& schema();

  std::string label() const override { return "Refine '" + p_.object + "' for its FFD"; }

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  RefineOptions options() const;
};

}  // namespace trispline::core
