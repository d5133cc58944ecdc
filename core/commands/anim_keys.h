// Keyframe lists of the animation commands (anim.keyframe, ddm.animate, incision.animate, dffd.animate): interpolation
// names, [frame, value…] rows made keys on the scene's timeline, and the check of a keyed blend weight.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/params/params.h"
#include "core/scene/scene.h"
#include "core/spline/keyframes.h"

namespace trispline::core {

// "linear" | "constant" | "smooth", and back (anything else: linear).
const char* interpolation_name(KeyInterpolation k);
KeyInterpolation interpolation_of(const std::string& name);

// Largest |s| of a keyed blend weight (incision.animate's opening, dffd.animate's stitch): 1 is the state as built, so
// ±100 leaves room for any deliberate exaggeration while keeping the extrapolated surface finite.
inline constexpr double kMaxKeyedWeight = 100.0;

// The params check of a keyed weight's [frame, s] list (incision.animate "opening_keys", dffd.animate
// "stitch_keys"): at least one key unless `clear`, every key finite with |s| ≤ kMaxKeyedWeight. `built` names s = 1
// in the message ("opening", "stitched seam"). Throws params::fail(field, …).
void check_weight_keys(const std::optional<std::vector<glm::dvec2>>& keys, bool clear, const char* field,
                       const char* built);

// Keys of a keyed weight from its [frame, s] list: keys_from_frames with the weight in .offset.x.
std::vector<OffsetKey> weight_keys_from_frames(const std::vector<glm::dvec2>& keys, const Timeline& timeline,
                                               KeyInterpolation interpolation, const char* field);

// Keys from (timeline frame, value…) rows (ddm.animate's and incision.animate's key lists): each row's frame becomes
// its scene time with `timeline`, its values the key's .offset (x, y; `two` = false: x only), sorted by time. Throws
// CommandError (field `field`) when two keys fall on one frame.
std::vector<OffsetKey> keys_from_frames(const std::vector<glm::dvec3>& rows, bool two, const Timeline& timeline,
                                        KeyInterpolation interpolation, const char* field);

// The line of a command that keys a blend weight s on the timeline (incision.animate's opening, dffd.animate's seam):
// the object, "clear" (back to the state as built), the [frame, s] keys under the command's own field name, and the
// interpolation of this line's keys.
struct KeyedWeightParams {
  std::string object;
  bool clear = false;
  std::optional<std::vector<glm::dvec2>> keys;  // (timeline frame, s)
  std::string interpolation = "linear";         // "linear" | "constant" | "smooth"
};

// What differs between the keyed-weight commands' declarations.
struct KeyedWeightDoc {
  const char* id;           // "incision.animate"
  const char* summary;      // the command's one line
  const char* object_help;  // which objects it takes
  const char* clear_help;   // what "clear" gives back
  const char* keys_field;   // "opening_keys"
  const char* keys_help;    // what s = 0 and s = 1 mean
  const char* built;        // s = 1 in messages ("opening", "stitched seam")
};

// The declaration of a keyed-weight command's line (check_weight_keys on its keys).
ParamSchema<KeyedWeightParams> keyed_weight_schema(const KeyedWeightDoc& doc);

// The keys of a keyed-weight line on `timeline` (weight_keys_from_frames); empty without keys.
std::vector<OffsetKey> keyed_weights(const KeyedWeightParams& p, const Timeline& timeline, const char* field);

}  // namespace trispline::core
