// Animation commands (seed §2.4.3: objects walking along the sketched path; two-level animation with a glTF clip).
//
//   {"cmd":"anim.keyframe","object":"ID","frame":F,"offset":[du,dv,dw],"interpolation":"linear|constant|smooth"}
//       Keys the object's FFD parameter offset (parameter units; du moves it along the stroke) at timeline frame F
//       (converted to scene time with the current timeline: (F − start)/fps seconds; F may lie outside the range).
//       "u":du may replace "offset" (v = w = 0). A key at the same time is replaced. interpolation (default linear)
//       shapes the segment that starts at this key. {"cmd":"anim.keyframe","object":"ID","frame":F,"remove":true}
//       deletes the key at F (error when there is none).
// Errors (CommandError, field named): unknown object, object without an FFD, NaN offsets, no key to remove.
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

class AnimKeyframeCommand : public ObjectSnapshotCommand<AnimKeyframeCommand, AnimKeyframeParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<AnimKeyframeParams>& schema();

  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
