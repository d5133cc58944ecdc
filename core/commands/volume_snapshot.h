// trispline::core::VolumeSnapshotCommand — base for commands that create, change or remove one volume (seed ch. 7):
// the new VolumeObject is built completely before the scene is touched; undo restores the snapshot taken before redo
// (splines, singleton tables and silhouettes are shared immutable pointers, so snapshots cost a few pointers).
#pragma once

#include <optional>

#include "core/commands/command.h"
#include "core/scene/scene.h"

namespace trispline::core {

class VolumeSnapshotCommand : public Command {
 public:
  void redo(Scene& scene) final;
  void undo(Scene& scene) final;
  nlohmann::json stats() const override { return stats_; }

 protected:
  virtual std::string target() const = 0;
  // The volume's new state (std::nullopt = remove it). Called once, on the first redo; must not modify the scene.
  // Anything it throws is reported as CommandError (field failure_field() unless it is a CommandError) and the scene
  // is unchanged.
  virtual std::optional<VolumeObject> build(const Scene& scene) = 0;
  virtual std::string failure_field() const { return {}; }

  nlohmann::json stats_ = nlohmann::json::object();

 private:
  bool built_ = false;
  std::optional<VolumeObject> before_, after_;
  int index_ = -1;
};

// The volume named `name`. Throws CommandError (field `field`): no volume of that name (naming the object when the
// name is a mesh object's).
const VolumeObject& require_volume(const Scene& scene, const std::string& name, const char* field = "object");

// `volume` with its silhouettes extracted for `camera` under its settings (null when disabled). Fills `stats` (points,
// polylines, length_mm, candidates, seeds, extract_ms, hidden_ms, max_value_residual, max_dot_residual).
VolumeObject volume_with_silhouettes(const VolumeObject& volume, const Camera& camera, nlohmann::json* stats = nullptr);

}  // namespace trispline::core
