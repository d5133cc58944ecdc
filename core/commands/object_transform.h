// `object.transform` — sets an object's location, rotation and scale (Blender's Object ▸ Transform, the G / R / S
// modal and the Scene panel's fields). Fields: declared in object_transform.cpp (ParamSchema), listed in
// docs/commands.md. The values are absolute, in SceneObject::transform's terms (scale, then rotation about x, then y,
// then z, then translation).
// The object moves with everything it carries: an FFD lattice, a DFFD rig and a placement record are mapped by the
// same affine change A = M(new)·M(old)⁻¹ (control points, embedding, contact samples; per-vertex parameters are kept),
// so the deformed shape moves rigidly with the object; tile layers live in object space and follow by themselves.
// Undo restores the object bit for bit (SnapshotCommand).
// Errors beyond the declared ranges (CommandError, field named, scene untouched): unknown object (`object`); a lattice
// object whose scale would change sign (a mirrored lattice; `scale`); a result with non-finite vertices (the field that
// changed most, `scale` if several).
// stats(): vertices, lattice_moved (0/1), ms_evaluate.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

// Limits of object.transform's fields (also used by the editor's fields to clamp what is typed).
inline constexpr double kMaxTranslate = 1e9;  // |component|, world units
inline constexpr double kMaxRotateDeg = 1e6;  // |component|, degrees
inline constexpr double kMaxScale = 1e6;      // scale components are in (0, kMaxScale]

// Throws CommandError naming the field when `t` breaks the limits above.
void check_transform(const Transform& t);

// `object` with transform `t`; its lattice / DFFD rig / placement record are mapped by A = M(t)·M(object.transform)⁻¹.
// exact: world_mesh is evaluated again (refresh(), what the command stores); otherwise world_mesh becomes
// A·world_mesh (an affine map of the current evaluation, for live previews: O(#V), no FFD evaluation).
// Throws CommandError (`scale`) when the object has a lattice and det A ≤ 0.
SceneObject object_with_transform(const SceneObject& object, const Transform& t, bool exact = true);

struct ObjectTransformParams {
  std::string object;
  std::optional<glm::dvec3> translate, rotate_deg, scale;  // absolute; unset = unchanged
};

class ObjectTransformCommand : public ObjectSnapshotCommand<ObjectTransformCommand, ObjectTransformParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static Schema declare();
  // The command setting `t` completely (all three fields), as the editor logs it.
  static CommandPtr make(const std::string& object, const Transform& t);

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
