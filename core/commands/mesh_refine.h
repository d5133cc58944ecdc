// `mesh.refine` — adaptive refinement of a deformed object's rest mesh so that its deformed edges follow the FFD
// (seed §2.4.2, Eq. 2.6, Fig. 2.9–2.10; core/ffd/refine.h has the algorithm). Fields: declared in mesh_refine.cpp
// (ParamSchema), listed in docs/commands.md. The greville criterion is the seed's split at the nodal value of the
// farthest control point of the composed curve, the tolerance on that control point's distance from the chord;
// midpoint is Chua & Neumann's (Eq. 2.6).
// The refinement runs in the object's space (rest_mesh) with the binding's parameters: the object's transform and the
// embedding are affine, so splitting an edge at t in object space is the same point as in world rest space; the
// object keeps its transform, lattice and embedding and gets a new binding with the interpolated parameters. Splits
// account for the object's param_offset (the shown pose). Undo restores the object as it was.
// Errors beyond the declared ranges (CommandError, field named): unknown object / object without an FFD / a glTF clip
// on it ("object"), tolerance below kMinRefineTolerance × the object's size ("tolerance"), best without error bound
// ("criterion"), max_triangles below the object's triangle count ("max_triangles").
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
  static Schema declare();

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  RefineOptions options() const;
};

}  // namespace trispline::core
