// `anim.record` — asks for the timeline's frames to be recorded (seed §2.4.3 animation sequences). Fields: declared
// in anim_record.cpp (ParamSchema), listed in docs/commands.md. The caller's default folder is the editor's
// "<log stem>_record/" or replay's --out; the scene camera is the last camera.set, else one framing the scene. Beyond
// the declared sizes the recorder checks the frame against the GL implementation's limits (GL_MAX_RENDERBUFFER_SIZE,
// GL_MAX_VIEWPORT_DIMS).
//
// The command does not change the scene: redo() checks the request against the scene's timeline and keeps it
// (request()), and whoever executed it (the editor's Record button, replay) runs editor::Recorder with it. Undo is a
// no-op; the command is in the log so that replaying a session records what the artist recorded. A FileOutput
// (core/commands/file_output.h): whoever executes it records only when writes_files() (Open and crash recovery
// replay it without recording; headless replay records under --out).
// Errors beyond the declared ranges (CommandError, field named): frames outside the timeline or A > B ("frames"),
// width without height or the other way round ("width"/"height"), more than kMaxRecordPixels in all ("width").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/commands/declared_command.h"
#include "core/commands/file_output.h"

namespace trispline::core {

// Pixels a recorded frame may have (8192 × 8192): 4× MSAA colour + depth take 32 bytes a pixel (2 GiB here).
inline constexpr std::int64_t kMaxRecordPixels = std::int64_t(8192) * 8192;

// "" when a width × height frame (pixels) is within kMaxRecordPixels; else the refusal, naming the sizes and the
// memory they would take (for anim.record, replay's and farm's --width / --height, farm.json). Inline: the farm's
// plan reader links no command.
inline std::string frame_budget_problem(std::int64_t width, std::int64_t height) {
  if (width * height <= kMaxRecordPixels) return {};
  return "a frame of " + std::to_string(width) + "×" + std::to_string(height) + " pixels is over the budget of " +
         std::to_string(kMaxRecordPixels / (1 << 20)) +
         " megapixels (8192×8192): its 4× multisampled colour and depth alone would need " +
         std::to_string(width * height * 32 >> 30) + " GiB";
}

// What a recording makes: anim.record's request (RecordRequest) and the recorder's options (editor::RecordOptions)
// both start with it.
struct RecordOutputs {
  std::string format = "png";           // "png" | "exr"
  int frame_first = 0, frame_last = 0;  // inclusive timeline frame numbers; both 0 = the whole timeline
  int width = 0, height = 0;            // pixels in [1, 16384], both or neither; 0 = the camera's viewport
  bool glb = true;                      // write animation.glb
  bool mp4 = true;                      // write animation.mp4 when ffmpeg is available (reported when it is not)
  std::optional<Camera> camera;         // the view every frame is rendered from; unset = the scene camera
};

// What anim.record asks for, with the frame range resolved against the timeline by redo() (never 0/0 after it unless
// the timeline is).
struct RecordRequest : RecordOutputs {
  std::string out;                // as in the log ("" = the caller's default)
  std::filesystem::path out_dir;  // `out` resolved against the log's folder ("" when out is "")
  bool frames_given = false;      // "frames" was in the line (else: the whole timeline at redo time)
};

// "" when [first, last] is a valid range of `timeline`, else the reason ("frames 100–130 lie outside the timeline
// 1–120"). Shared by anim.record and editor::validate_record_options.
std::string frame_range_error(const Timeline& timeline, int first, int last);

// The fields of an anim.record line.
struct AnimRecordParams {
  std::string out;                   // folder, as written in the log ("" = the caller's default)
  std::string format = "png";        // png | exr
  std::optional<glm::ivec2> frames;  // inclusive timeline frames; unset = the whole timeline at redo time
  bool glb = true, mp4 = true;
  std::optional<int> width, height;  // pixels; unset = the camera's viewport
  std::optional<Camera> camera;      // the view recorded (camera.set's fields); unset = the scene camera
};

class AnimRecordCommand : public DeclaredCommand<AnimRecordCommand, AnimRecordParams>, public FileOutput {
 public:
  explicit AnimRecordCommand(AnimRecordParams p, const std::filesystem::path& base_dir = {});
  static Schema declare();
  // As DeclaredCommand::parse, and `out` is resolved against the log's folder.
  static CommandPtr parse(const nlohmann::json& line, const CommandContext& ctx);

  std::string label() const override;
  // Validates against scene.timeline (the scene is not modified); files_written() from then on when writes_files().
  void redo(Scene& scene) override;
  void undo(Scene&) override {}
  bool undoable() const override { return false; }  // logged for replays, never an undo step
  nlohmann::json stats() const override;
  std::filesystem::path output_path() const override { return request_.out_dir; }  // "" = the caller's default

  // The request; frame_first/frame_last are resolved by the last redo() (the whole timeline when not given).
  const RecordRequest& request() const { return request_; }

 private:
  RecordRequest request_;
};

}  // namespace trispline::core
