// `anim.timeline` — the scene's frame range and rate (core::Timeline; seed §2.4.3 animation sequences). Fields:
// declared in anim_timeline.cpp (ParamSchema), listed in docs/commands.md. Omitted fields keep their current value.
// Undo restores the previous timeline.
// Errors beyond the declared ranges (CommandError, field named): none of fps, start, end given ("fps"); an end before
// the start once the line is applied to the current timeline ("end", or "start" when only start is given).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct AnimTimelineParams {
  std::optional<double> fps;  // frames per second
  std::optional<int> start, end;
};

class AnimTimelineCommand : public DeclaredCommand<AnimTimelineCommand, AnimTimelineParams> {
 public:
  static Schema declare();

  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  Timeline before_;
};

}  // namespace trispline::core
