#include "core/commands/anim_record.h"

#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

std::string frame_range_error(const Timeline& timeline, int first, int last) {
  const std::string range = std::to_string(timeline.frame_start) + "-" + std::to_string(timeline.frame_end);
  if (first > last) return "first frame " + std::to_string(first) + " is after the last frame " + std::to_string(last);
  if (first < timeline.frame_start || last > timeline.frame_end)
    return "frames " + std::to_string(first) + "-" + std::to_string(last) + " lie outside the timeline " + range;
  return {};
}

CommandPtr AnimRecordCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<AnimRecordCommand>();
  RecordRequest& r = c->request_;
  r.out = jf::get_string(j, "out", "");
  if (!r.out.empty()) r.out_dir = std::filesystem::absolute(ctx.resolve(r.out)).lexically_normal();
  r.format = jf::get_enum(j, "format", {"png", "exr"}, "png");
  if (jf::has(j, "frames")) {
    const glm::ivec2 f = jf::get_ivec2(j, "frames");
    if (f.x > f.y)
      throw CommandError(
          "field 'frames': first frame " + std::to_string(f.x) + " is after the last frame " + std::to_string(f.y),
          "frames");
    r.frame_first = f.x;
    r.frame_last = f.y;
    r.frames_given = true;
  }
  r.glb = jf::get_bool(j, "glb", true);
  r.mp4 = jf::get_bool(j, "mp4", true);
  r.width = jf::get_int(j, "width", 0);
  r.height = jf::get_int(j, "height", 0);
  for (const char* field : {"width", "height"}) {
    const int v = std::string(field) == "width" ? r.width : r.height;
    if (jf::has(j, field) && (v < 1 || v > 16384))
      throw CommandError(std::string("field '") + field + "': must be in [1, 16384] pixels, got " + std::to_string(v),
                         field);
  }
  if (jf::has(j, "width") != jf::has(j, "height")) {
    const char* missing = jf::has(j, "width") ? "height" : "width";
    throw CommandError(std::string("field '") + missing + "': give width and height together", missing);
  }
  if (std::int64_t(r.width) * r.height > kMaxRecordPixels)
    throw CommandError("field 'width': a frame of " + std::to_string(r.width) + "×" + std::to_string(r.height) +
                           " pixels is over the budget of " + std::to_string(kMaxRecordPixels / (1 << 20)) +
                           " megapixels (8192×8192): its 4× multisampled colour and depth alone would need " +
                           std::to_string(std::int64_t(r.width) * r.height * 32 >> 30) + " GiB",
                       "width");
  return c;
}

nlohmann::json AnimRecordCommand::to_json() const {
  const RecordRequest& r = request_;
  nlohmann::json j = {{"cmd", id()}};
  if (!r.out.empty()) j["out"] = r.out;
  j["format"] = r.format;
  if (r.frames_given) j["frames"] = {r.frame_first, r.frame_last};
  j["glb"] = r.glb;
  j["mp4"] = r.mp4;
  if (r.width > 0) {
    j["width"] = r.width;
    j["height"] = r.height;
  }
  return j;
}

std::string AnimRecordCommand::label() const {
  if (!request_.frames_given) return "Record the timeline";
  return "Record frames " + std::to_string(request_.frame_first) + "-" + std::to_string(request_.frame_last);
}

void AnimRecordCommand::redo(Scene& scene) {
  const Timeline& t = scene.timeline;
  const int first = request_.frames_given ? request_.frame_first : t.frame_start;
  const int last = request_.frames_given ? request_.frame_last : t.frame_end;
  const std::string err = frame_range_error(t, first, last);
  if (!err.empty()) throw CommandError("field 'frames': " + err, "frames");
  request_.frame_first = first;
  request_.frame_last = last;
}

nlohmann::json AnimRecordCommand::stats() const {
  return {{"frame_first", request_.frame_first},
          {"frame_last", request_.frame_last},
          {"frames", request_.frame_last - request_.frame_first + 1}};
}

}  // namespace trispline::core
