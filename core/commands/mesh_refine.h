// `mesh.refine` — adaptive refinement of a deformed object's rest mesh so that its deformed edges follow the FFD
// (seed §2.4.2, Eq. 2.6, Fig. 2.9–2.10; core/deform/refine.h has the algorithm).
//   {"cmd":"mesh.refine","object":"ID","tolerance":t,"criterion":"midpoint|greville","max_iterations":n,
//    "max_triangles":m}
// tolerance: world units (> 0, finite); criterion: "greville" (default; the seed's split at the nodal value of the
// farthest control point of the composed curve, tolerance on that control point's distance from the chord) or
// "midpoint" (Chua & Neumann, Eq. 2.6); max_iterations: split rounds (default 16, 0..64); max_triangles: a round
// that would exceed it is not applied (default 2,000,000, ≥ the object's triangle count, ≤ 50,000,000).
// The refinement runs in the object's space (rest_mesh) with the binding's parameters: the object's transform and the
// embedding are affine, so splitting an edge at t in object space is the same point as in world rest space; the
// object keeps its transform, lattice and embedding and gets a new binding with the interpolated parameters. Splits
// account for the object's param_offset (the shown pose). Undo restores the object as it was.
// Errors (CommandError, field named): unknown object / object without an FFD ("object"), tolerance ≤ 0 or not
// finite ("tolerance"), unknown criterion ("criterion"), limits out of range ("max_iterations", "max_triangles").
#pragma once

#include "core/commands/snapshot_command.h"
#include "core/deform/refine.h"

namespace trispline::core {

class MeshRefineCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "mesh.refine"; }
  nlohmann::json to_json() const override;
  std::string label() const override { return "Refine '" + object_ + "' for its FFD"; }
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_;
  RefineOptions options_;
  nlohmann::json stats_ = nlohmann::json::object();
};

}  // namespace trispline::core
