#include "core/commands/anim_keys.h"

#include <algorithm>
#include <cmath>

#include "core/base/enum_names.h"
#include "core/params/params.h"

namespace trispline::core {

const char* interpolation_name(KeyInterpolation k) { return enum_name(k, {"constant", "linear", "smooth"}, "linear"); }

KeyInterpolation interpolation_of(const std::string& name) {
  return name == "constant" ? KeyInterpolation::constant
         : name == "smooth" ? KeyInterpolation::smooth
                            : KeyInterpolation::linear;
}

void check_weight_keys(const std::optional<std::vector<glm::dvec2>>& keys, bool clear, const char* field,
                       const char* built) {
  if (!clear && (!keys || keys->empty())) params::fail(field, "give at least one [frame, s] key (or \"clear\":true)");
  if (keys)
    for (const glm::dvec2& k : *keys)
      if (!std::isfinite(k.x) || !std::isfinite(k.y) || std::abs(k.y) > kMaxKeyedWeight)
        params::fail(field, std::string("keys must be finite with s within ±100 (s = 1 is the ") + built +
                                " as built; beyond ±100 the extrapolated surface leaves any sensible range)");
}

std::vector<OffsetKey> weight_keys_from_frames(const std::vector<glm::dvec2>& keys, const Timeline& timeline,
                                               KeyInterpolation interpolation, const char* field) {
  std::vector<glm::dvec3> rows;
  rows.reserve(keys.size());
  for (const glm::dvec2& k : keys) rows.push_back({k.x, k.y, 0.0});
  return keys_from_frames(rows, false, timeline, interpolation, field);
}

std::vector<OffsetKey> keys_from_frames(const std::vector<glm::dvec3>& rows, bool two, const Timeline& timeline,
                                        KeyInterpolation interpolation, const char* field) {
  std::vector<OffsetKey> keys;
  for (const glm::dvec3& r : rows)
    keys.push_back(
        {timeline.time_of_frame(r.x), two ? glm::dvec3(r.y, r.z, 0.0) : glm::dvec3(r.y, 0.0, 0.0), interpolation});
  std::sort(keys.begin(), keys.end(), [](const OffsetKey& a, const OffsetKey& b) { return a.time_s < b.time_s; });
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].time_s == keys[i - 1].time_s)
      throw CommandError(std::string("field '") + field + "': two keys on frame " +
                             std::to_string(timeline.frame_of_time(keys[i].time_s)),
                         field);
  return keys;
}

ParamSchema<KeyedWeightParams> keyed_weight_schema(const KeyedWeightDoc& doc) {
  using P = KeyedWeightParams;
  const char* field = doc.keys_field;
  const char* built = doc.built;
  return ParamSchema<P>(doc.id, doc.summary)
      .field("object", &P::object, {.required = true, .help = doc.object_help})
      .field("clear", &P::clear, {.write = ParamWrite::UnlessDefault, .help = doc.clear_help})
      .field(field, &P::keys, {.default_text = "kept", .type_text = "[[frame,s],…]", .help = doc.keys_help})
      .choice("interpolation", &P::interpolation, {"linear", "constant", "smooth"},
              {.write = ParamWrite::UnlessDefault, .help = "How this line's keys move to the next key"})
      .check([field, built](const P& p) { check_weight_keys(p.keys, p.clear, field, built); });
}

std::vector<OffsetKey> keyed_weights(const KeyedWeightParams& p, const Timeline& timeline, const char* field) {
  if (!p.keys) return {};
  return weight_keys_from_frames(*p.keys, timeline, interpolation_of(p.interpolation), field);
}

}  // namespace trispline::core
