// trispline::editor recording — renders a range of timeline frames to numbered images, an animated GLB and an MP4
// (seed §2.4.3 animation sequences; the anim.record command, the editor's Record button, replay --frames).
//
// Every frame is rendered from core::scene_at_time(s, timeline.time_of_frame(f)), s = core::render_visible_scene(scene)
// (objects and volumes out of renders are left out before anything is posed or drawn), by one persistent headless
// renderer (EGL surfaceless; llvmpipe when there is no GPU), at a fixed size, with the scene's camera. A frame
// depends only on the scene and its frame number — never on the frames rendered before it — so any split of a
// range (a render farm) writes the same bytes per frame as a full recording.
//
// Files in out_dir (created if missing):
//   frame_NNNN.png | frame_NNNN.exr   NNNN = timeline frame number, 4 digits (more when ≥ 10000); PNG 8-bit sRGB
//                                     RGBA, EXR half-float linear RGBA; no time stamps in the files
//   animation.glb                     (glb = true) the recorded frames as one glTF: per object one mesh whose
//                                     morph targets are the per-frame positions/normals relative to the first
//                                     recorded frame, and one animation whose STEP weight channel shows target k
//                                     at frame k (Blender imports these as shape keys with keyed values)
//   animation.piece                   (glb = true and piece_base ≥ 0, instead of animation.glb) the same frames
//                                     relative to frame piece_base, for joining chunks (render farm)
//   animation.mp4                     (mp4 = true, only when `ffmpeg` is on PATH) H.264, yuv420p, timeline fps
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/commands/anim_record.h"
#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"

namespace trispline::editor {

// The recorder's options: what it makes (core::RecordOutputs: format, frames, size, glb, mp4, camera; the camera
// unset: see above) and where and how.
struct RecordOptions : core::RecordOutputs {
  std::filesystem::path out_dir;  // required (created if missing)
  // false: render nothing and write no frame files, only pose every frame for animation.glb (and make the MP4 from
  // the frame_NNNN.png files already in out_dir): a render farm's assemble step. No GL context is needed.
  bool images = true;
  // ≥ 0: write animation.piece (core::MorphAnimationBuilder::write_piece) instead of animation.glb, its first frame
  // the pose of this timeline frame (posed, not rendered, when it is before frame_first): one chunk of a render
  // farm's range, joined exactly by `trispline farm assemble`. Must lie in [timeline start, frame_first].
  int piece_base = -1;
  core::FfdBackend ffd_backend = core::FfdBackend::cpu_ref;  // geometry path (cpu_ref: bit-exact frames)
};

// The options of an executed anim.record (its resolved frames, size, format, outputs and camera), written into
// `out_dir`.
RecordOptions record_options(const core::RecordRequest& request, std::filesystem::path out_dir);

// What a recording produced (report.json "record", the editor's message log).
struct RecordResult {
  int frames_written = 0;
  int frame_first = 0, frame_last = 0;
  bool cancelled = false;
  std::vector<std::filesystem::path> files;  // every file written, in order
  std::string glb;                           // path, or "" when not written
  std::string mp4;                           // path, or "" when not written
  std::string mp4_note;                      // why there is no MP4 ("ffmpeg not found on PATH", ffmpeg's error)
  double ms = 0;                             // wall time
  nlohmann::json to_json() const;
};

// Checks options against the scene's timeline. Throws std::invalid_argument naming the problem: range outside the
// timeline (frame_first < frame_start or frame_last > frame_end), first > last, unknown format, bad size.
void validate_record_options(const core::Scene& scene, const RecordOptions& options);

// Incremental recorder: step() renders and writes one frame, so the editor can draw a progress bar (frames done,
// time left) and cancel between frames. Construction validates (validate_record_options; nothing is written when it
// throws), creates out_dir and sets up a HeadlessRenderer (editor/replay/render_scene.h); it throws
// std::invalid_argument, gpu::GlContextError or std::runtime_error. The scene is copied. GL context: when a context is
// current on the calling thread at construction (the editor's window), the recorder draws with it into its own
// offscreen target — step() and the destructor must then run with that context current (it restores the framebuffer
// binding and viewport after each frame); otherwise it makes a private EGL context. The camera is options.camera, else
// the scene's (framing_camera of the un-posed scene when none was set), fixed for all frames (its viewport replaced by
// width × height when given); clip planes are fitted to each posed frame. The viewport's ground grid is not drawn.
class Recorder {
 public:
  Recorder(const core::Scene& scene, RecordOptions options);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Renders and writes the next frame and returns true; returns false without rendering when all frames are done
  // or after cancel(), so `while (recorder.step()) {}` records everything. Throws std::runtime_error when a file
  // cannot be written (frames already written stay).
  bool step();
  void cancel();
  int frames_done() const;
  int frames_total() const;
  double seconds_left() const;  // estimate from the mean frame time so far (< 0 before the first frame)
  int current_frame() const;    // timeline frame the next step() renders
  // Writes animation.glb / animation.mp4 for the frames written (neither when cancelled) and returns the result;
  // frames not yet rendered are not rendered (the result says how many were). A second call returns the same result.
  // Throws std::runtime_error when animation.glb cannot be written; an MP4 failure is reported in mp4_note.
  RecordResult finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Blocking convenience: Recorder until done, then finish(). `progress` (optional) is called after every frame with
// (done, total); returning false cancels.
RecordResult record_frames(const core::Scene& scene, const RecordOptions& options,
                           const std::function<bool(int, int)>& progress = {});

// The whole timeline when options.frame_first and frame_last are both 0, else [frame_first, frame_last].
std::pair<int, int> record_range(const core::Scene& scene, const RecordOptions& options);

// "frame_0007.png" for frame 7 and format "png".
std::string frame_file_name(int frame, const std::string& format);

// Makes dir/animation.mp4 (H.264, yuv420p, `fps` frames per second) from the `frames` files dir/frame_NNNN.png
// numbered from timeline frame `first`; an odd width or height (pixels) is padded by a black row or column. Returns
// "" when it was written, otherwise why not ("ffmpeg not found on PATH", ffmpeg's error); never throws.
std::string write_mp4(const std::filesystem::path& dir, int first, int frames, double fps, int width, int height);

// Absolute path of the executable `name` found on PATH, or an empty path when there is none.
std::filesystem::path find_on_path(const std::string& name);

}  // namespace trispline::editor
