// Animation commands (seed §2.4.3: objects walking along the sketched path; two-level animation with a glTF clip).
//
//   {"cmd":"anim.timeline","fps":24,"start":1,"end":120}
//       The scene's frame range and rate (core::Timeline). fps in [0.01, 240]; 0 ≤ start ≤ end ≤ 100000. Omitted fields
//       keep their current value. Undo restores the previous timeline.
// Errors (CommandError, field named): non-finite numbers, fps or range out of bounds.
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
  using DeclaredCommand::DeclaredCommand;
  static const ParamSchema<AnimTimelineParams>& schema();

  std::string label() const override;
  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  Timeline before_;
};

}  // namespace trispline::core
