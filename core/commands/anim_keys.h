// Keyframe lists of the animation commands (anim.keyframe, ddm.animate, incision.animate, dffd.animate): interpolation
// names, [frame, value…] rows made keys on the scene's timeline, and the check of a keyed blend weight.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

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

}  // namespace trispline::core
