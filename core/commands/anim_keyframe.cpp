#include "core/commands/anim_keyframe.h"

#include <cmath>

namespace trispline::core {

auto AnimKeyframeCommand::declare() -> Schema {
  return Schema("anim.keyframe",
                "Key (or delete a key of) an object's parameter offset along its path at a frame (seed §2.4.3)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (FFD or DFFD)"})
      .field(
          "frame", &P::frame,
          {.required = true, .range = ParamRange::magnitude_at_most(1e6), .help = "Timeline frame (may be fractional)"})
      .field("remove", &P::remove, {.write = ParamWrite::UnlessDefault, .help = "Delete the key at this frame instead"})
      .stop_if([](const P& p) { return p.remove; })
      .field("offset", &P::offset,
             {.range = ParamRange::magnitude_at_most(1e6),
              .unit = "parameter units",
              .help = "Parameter offset [du,dv,dw] at the key (or give \"u\")"})
      .field("u", &P::u,
             {.range = ParamRange::magnitude_at_most(1e6), .unit = "parameter units", .help = "The u offset alone"})
      .check([](P& p) {
        if (p.offset)
          p.u.reset();  // "offset" wins
        else if (!p.u)
          params::fail("offset", "missing (give \"offset\":[du,dv,dw] or \"u\":du)");
      })
      .choice("interpolation", &P::interpolation, {"linear", "constant", "smooth"},
              {.help = "How the offset goes from this key to the next"})
      .label([](const P& p) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "%g", p.frame);
        return (p.remove ? "Delete keyframe of '" : "Keyframe '") + p.object + "' at frame " + buf;
      });
}

std::optional<SceneObject> AnimKeyframeCommand::build(const Scene& scene) {
  // An FFD object, or a DFFD object (dffd.split): both read their parameter offset at every scene time.
  const SceneObject* found = scene.find(p_.object);
  SceneObject out = found && found->dffd ? *found : require_deformed_object(scene, p_.object);
  const double t = scene.timeline.time_of_frame(p_.frame);
  auto& keys = out.offset_keys;
  // Keys closer than a microsecond are the same key (frames convert through a division).
  auto same = std::find_if(keys.begin(), keys.end(), [&](const OffsetKey& k) { return std::abs(k.time_s - t) < 1e-6; });
  if (p_.remove) {
    if (same == keys.end())
      throw CommandError(
          "field 'frame': object '" + p_.object + "' has no keyframe at frame " + std::to_string(p_.frame), "frame");
    keys.erase(same);
  } else if (same != keys.end()) {
    same->offset = p_.key_offset();
    same->interpolation = interpolation_of(p_.interpolation);
  } else {
    const auto at =
        std::upper_bound(keys.begin(), keys.end(), t, [](double x, const OffsetKey& k) { return x < k.time_s; });
    keys.insert(at, OffsetKey{t, p_.key_offset(), interpolation_of(p_.interpolation)});
  }
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();  // the t = 0 pose follows the keys
  stats_ = {{"keys", keys.size()},
            {"time_s", t},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
