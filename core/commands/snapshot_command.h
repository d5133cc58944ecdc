// trispline::core::SnapshotCommand — base for commands that create, change or remove one named object
// (BasicSnapshotCommand<SceneObject>; VolumeSnapshotCommand is the same for volumes).
// The new object is built completely (build()) before the scene is touched; undo restores the snapshot taken
// before redo. Meshes are shared immutable pointers, so snapshots cost a few pointers, not mesh copies, and
// undo/redo restore meshes bit for bit. build() may record figures in stats_ (reported by stats()).
#pragma once

#include <optional>

#include "core/commands/command.h"

namespace trispline::core {

// Where a snapshot command finds, puts and takes its kind of named item in a Scene.
template <class T>
struct SnapshotSlots;

template <>
struct SnapshotSlots<SceneObject> {
  static int index_of(const Scene& s, const std::string& name) { return s.index_of(name); }
  static const SceneObject& at(const Scene& s, int i) { return s.objects()[i]; }
  static void replace(Scene& s, const SceneObject& o) { s.replace(o); }
  static void insert(Scene& s, const SceneObject& o, int i) { s.insert(o, i); }
  static void remove(Scene& s, const std::string& name) { s.remove(name); }
};

template <>
struct SnapshotSlots<VolumeObject> {
  static int index_of(const Scene& s, const std::string& name) { return s.volume_index_of(name); }
  static const VolumeObject& at(const Scene& s, int i) { return s.volumes()[i]; }
  static void replace(Scene& s, const VolumeObject& v) { s.replace_volume(v); }
  static void insert(Scene& s, const VolumeObject& v, int i) { s.insert_volume(v, i); }
  static void remove(Scene& s, const std::string& name) { s.remove_volume(name); }
};

template <class T>
class BasicSnapshotCommand : public Command {
 public:
  void prepare(const Scene& scene, const ProgressSink& progress) final {
    if (!preparable() || built_) return;
    progress_ = &progress;
    try {
      run_build(scene);
    } catch (...) {
      progress_ = nullptr;
      throw;
    }
    progress_ = nullptr;
  }
  void redo(Scene& scene) final {
    using Slots = SnapshotSlots<T>;
    if (!built_) run_build(scene);
    index_ = Slots::index_of(scene, target());
    if (index_ >= 0)
      before_ = Slots::at(scene, index_);
    else
      before_.reset();
    if (after_ && before_)
      Slots::replace(scene, *after_);
    else if (after_)
      Slots::insert(scene, *after_, -1);
    else if (before_)
      Slots::remove(scene, target());
  }
  void undo(Scene& scene) final {
    using Slots = SnapshotSlots<T>;
    if (Slots::index_of(scene, target()) >= 0) Slots::remove(scene, target());
    if (before_) Slots::insert(scene, *before_, index_);
  }
  nlohmann::json stats() const override { return stats_; }

 protected:
  // Name of the item this command changes (known after parsing).
  virtual std::string target() const = 0;
  // The item's new state (std::nullopt = remove it). Called once, on the first redo; must not modify the scene.
  // May throw anything derived from std::exception: it is reported as CommandError and the scene is unchanged.
  virtual std::optional<T> build(const Scene& scene) = 0;
  // Field to blame when build() throws something that is not a CommandError (e.g. "path" for I/O errors).
  virtual std::string failure_field() const { return {}; }
  // While prepare() runs build(): its progress sink (report, cancel flag), for build to pass down; else null.
  const ProgressSink* progress() const { return progress_; }

  nlohmann::json stats_ = nlohmann::json::object();  // what build() measured (counts, milliseconds)

 private:
  // build() once; its errors as CommandError (OperationCancelled passes through).
  void run_build(const Scene& scene) {
    try {
      after_ = build(scene);
    } catch (const CommandError&) {
      throw;
    } catch (const OperationCancelled&) {
      throw;
    } catch (const std::exception& e) {
      throw CommandError(e.what(), failure_field());
    }
    built_ = true;
  }

  bool built_ = false;
  const ProgressSink* progress_ = nullptr;
  std::optional<T> before_, after_;
  int index_ = -1;
};

using SnapshotCommand = BasicSnapshotCommand<SceneObject>;

// The object named `name`. Throws CommandError (field `field`): no object of that name.
const SceneObject& require_object(const Scene& scene, const std::string& name, const char* field = "object");

// The object named `name` when it has an FFD lattice. Throws CommandError (field 'object') naming what is wrong:
// no such object, or no lattice (place it with place.sketch or lattice.ring first).
const SceneObject& require_deformed_object(const Scene& scene, const std::string& name);

// `object` (deformed) rebuilt with `lattice` in place of its FFD lattice (same embedding and parameters) and
// evaluated; stats["ms_evaluate"] gets the evaluation's milliseconds. For the commands that move control points.
SceneObject with_lattice(const SceneObject& object, TrivariateBSpline<glm::dvec3> lattice, nlohmann::json& stats);

// Throws CommandError (field 'object') when `object` holds tile layers (SceneObject::ddm_layers, seed ch. 5) and
// `change` (e.g. "a subdivision") would replace the mesh they are laid on — not a deformation, which carries them
// (ddm_follow.h); the message names the layers and says to bake (ddm.bake) or remove (ddm.remove) them first.
void require_no_tile_layers(const SceneObject& object, const std::string& change);
// The world positions an FFD made for `object` must hold inside its box: its transformed rest mesh, then the vertices
// of every tile layer through the object's transform (tiles ride on the deformation after the DDM, ddm_follow.h, so
// thorns sticking out of the surface must be embedded too, not clamped flat against the box).
std::vector<glm::dvec3> positions_with_tile_layers(const SceneObject& object, const TriMesh& world_rest);

}  // namespace trispline::core
