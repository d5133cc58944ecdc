#include "core/commands/anim_record.h"

#include "core/params/codecs.h"

namespace trispline::core {

std::string frame_range_error(const Timeline& timeline, int first, int last) {
  const std::string range = std::to_string(timeline.frame_start) + "-" + std::to_string(timeline.frame_end);
  if (first > last) return "first frame " + std::to_string(first) + " is after the last frame " + std::to_string(last);
  if (first < timeline.frame_start || last > timeline.frame_end)
    return "frames " + std::to_string(first) + "-" + std::to_string(last) + " lie outside the timeline " + range;
  return {};
}

auto AnimRecordCommand::declare() -> Schema {
  return Schema("anim.record", "Record timeline frames to PNG/EXR images, an animated glb and an MP4 (seed §2.4.3)")
      .field("out", &P::out,
             {.write = ParamWrite::UnlessDefault,
              .default_text = "the caller's",
              .help = "Output folder, relative to the log's folder"})
      .choice("format", &P::format, {"png", "exr"}, {.help = "png: 8-bit sRGB; exr: half float, linear"})
      .field("frames", &P::frames,
             {.default_text = "the whole timeline",
              .help = "First and last timeline frame, inclusive, inside the timeline"})
      .check([](const P& p) {
        if (p.frames && p.frames->x > p.frames->y)
          params::fail("frames", "first frame " + std::to_string(p.frames->x) + " is after the last frame " +
                                     std::to_string(p.frames->y));
      })
      .field("glb", &P::glb, {.help = "Write animation.glb (one mesh per frame, shown in turn)"})
      .field("mp4", &P::mp4, {.help = "Write animation.mp4 when ffmpeg is installed"})
      .field("width", &P::width,
             {.range = ParamRange{1, 16384},
              .unit = "pixels",
              .default_text = "the camera's viewport",
              .help = "Frame width; give width and height together"})
      .field("height", &P::height,
             {.range = ParamRange{1, 16384},
              .unit = "pixels",
              .default_text = "the camera's viewport",
              .help = "Frame height"})
      .object(
          "camera", &P::camera, camera_schema(),
          {.default_text = "the scene camera",
           .help = "The view every frame is rendered from (camera.set's fields; the Record dialog's \"Current view\")"})
      .check([](const P& p) {
        if (p.width.has_value() != p.height.has_value()) {
          const char* missing = p.width ? "height" : "width";
          params::fail(missing, "give width and height together");
        }
        const std::string problem = frame_budget_problem(p.width.value_or(0), p.height.value_or(0));
        if (!problem.empty()) params::fail("width", problem);
      });
}

AnimRecordCommand::AnimRecordCommand(AnimRecordParams p, const std::filesystem::path& base_dir)
    : DeclaredCommand(std::move(p)) {
  RecordRequest& r = request_;
  r.out = p_.out;
  if (!r.out.empty())
    r.out_dir = std::filesystem::absolute(CommandContext{base_dir, {}}.resolve(r.out)).lexically_normal();
  r.format = p_.format;
  if (p_.frames) {
    r.frame_first = p_.frames->x;
    r.frame_last = p_.frames->y;
    r.frames_given = true;
  }
  r.glb = p_.glb;
  r.mp4 = p_.mp4;
  r.width = p_.width.value_or(0);
  r.height = p_.height.value_or(0);
  r.camera = p_.camera;
}

CommandPtr AnimRecordCommand::parse(const nlohmann::json& line, const CommandContext& ctx) {
  return std::make_unique<AnimRecordCommand>(schema().parse(line, ctx), ctx.base_dir);
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
  if (writes_files()) mark_written();  // the caller records it
}

nlohmann::json AnimRecordCommand::stats() const {
  return {{"frame_first", request_.frame_first},
          {"frame_last", request_.frame_last},
          {"frames", request_.frame_last - request_.frame_first + 1}};
}

}  // namespace trispline::core
