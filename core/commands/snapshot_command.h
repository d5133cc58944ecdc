// trispline::core::SnapshotCommand — base for commands that create, change or remove one named object.
// The new object is built completely (build()) before the scene is touched; undo restores the snapshot taken
// before redo. Meshes are shared immutable pointers, so snapshots cost a few pointers, not mesh copies, and
// undo/redo restore meshes bit for bit. build() may record figures in stats_ (reported by stats()).
#pragma once

#include <optional>

#include "core/commands/command.h"

namespace trispline::core {

class SnapshotCommand : public Command {
 public:
  void redo(Scene& scene) final;
  void undo(Scene& scene) final;
  nlohmann::json stats() const override { return stats_; }

 protected:
  // Name of the object this command changes (known after parsing).
  virtual std::string target() const = 0;
  // The object's new state (std::nullopt = remove it). Called once, on the first redo; must not modify the scene.
  // May throw anything derived from std::exception: it is reported as CommandError and the scene is unchanged.
  virtual std::optional<SceneObject> build(const Scene& scene) = 0;
  // Field to blame when build() throws something that is not a CommandError (e.g. "path" for I/O errors).
  virtual std::string failure_field() const { return {}; }

  nlohmann::json stats_ = nlohmann::json::object();  // what build() measured (counts, milliseconds)

 private:
  bool built_ = false;
  std::optional<SceneObject> before_, after_;
  int index_ = -1;
};

// The object named `name`. Throws CommandError (field `field`): no object of that name.
const SceneObject& require_object(const Scene& scene, const std::string& name, const char* field = "object");

// The object named `name` when it has an FFD lattice. Throws CommandError (field 'object') naming what is wrong:
// no such object, or no lattice (place it with place.sketch or lattice.ring first).
const SceneObject& require_deformed_object(const Scene& scene, const std::string& name);

// Throws CommandError (field 'object') when `object` holds tile layers (SceneObject::ddm_layers, seed ch. 5): they sit
// on its undeformed rest surface and would not follow `change` (e.g. "an FFD lattice", "an incision"); the message
// names the layers and says to bake (ddm.bake) or remove (ddm.remove) them first.
void require_no_tile_layers(const SceneObject& object, const std::string& change);

}  // namespace trispline::core
