#include "core/commands/anim_timeline.h"

#include <cmath>

namespace trispline::core {

auto AnimTimelineCommand::declare() -> Schema {
  return Schema("anim.timeline", "Set the timeline's frame range and frame rate")
      // At least one frame per 100 s: below that, frame times overflow long before a timeline ends (1e-320 fps).
      .field("fps", &P::fps, {.range = ParamRange{0.01, 240}, .unit = "frames per second", .help = "Frame rate"})
      .field("start", &P::start, {.range = ParamRange{0, 100000}, .help = "First frame"})
      .field("end", &P::end, {.range = ParamRange{0, 100000}, .help = "Last frame, ≥ start"})
      .check([](const P& p) {
        if (!p.fps && !p.start && !p.end) params::fail("fps", "give at least one of fps, start, end");
      })
      .label([](const P& p) {
        std::string s = "Timeline";
        if (p.start || p.end)
          s += " frames " + (p.start ? std::to_string(*p.start) : "…") + "-" + (p.end ? std::to_string(*p.end) : "…");
        if (p.fps) {
          char buf[32];
          std::snprintf(buf, sizeof buf, " at %g fps", *p.fps);
          s += buf;
        }
        return s;
      });
}

void AnimTimelineCommand::redo(Scene& scene) {
  Timeline t = scene.timeline;
  if (p_.fps) t.fps = *p_.fps;
  if (p_.start) t.frame_start = *p_.start;
  if (p_.end) t.frame_end = *p_.end;
  if (t.frame_end < t.frame_start)
    throw CommandError("field 'end': the last frame (" + std::to_string(t.frame_end) + ") is before the first frame (" +
                           std::to_string(t.frame_start) + ")",
                       p_.end ? "end" : "start");
  before_ = scene.timeline;
  scene.timeline = t;
}

void AnimTimelineCommand::undo(Scene& scene) { scene.timeline = before_; }

}  // namespace trispline::core
