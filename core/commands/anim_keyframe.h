// `anim.keyframe` — keys (or deletes a key of) an object's FFD parameter offset (seed §2.4.3: objects walking along
// the sketched path). Fields: declared in anim_keyframe.cpp (ParamSchema), listed in docs/commands.md. du moves the
// object along the stroke. The frame F is converted to scene time with the current timeline: (F − start)/fps seconds;
// F may lie outside the range. "u" alone keys [u, 0, 0]; "offset" wins when both are given. A key at the same time
// is replaced.
// Errors beyond the declared ranges (CommandError, field named): unknown object, object without an FFD or DFFD
// ("object"), no key to remove ("frame").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/commands/anim_keys.h"
#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct AnimKeyframeParams {
  std::string object;
  double frame = 0;
  bool remove = false;               // delete the key at `frame` instead
  std::optional<glm::dvec3> offset;  // parameter units
  std::optional<double> u;           // the u offset alone (kept as "u" in the log)
  std::string interpolation = "linear";
  glm::dvec3 key_offset() const { return offset ? *offset : glm::dvec3(u ? *u : 0.0, 0.0, 0.0); }
};

struct AnimKeyframeCommand : ObjectSnapshotCommand<AnimKeyframeCommand, AnimKeyframeParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
