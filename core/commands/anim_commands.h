// Animation commands (seed §2.4.3: objects walking along the sketched path; two-level animation with a glTF clip).
//
//   {"cmd":"anim.timeline","fps":24,"start":1,"end":120}
//       The scene's frame range and rate (core::Timeline). fps in [0.01, 240]; 0 ≤ start ≤ end ≤ 100000. Omitted fields
//       keep their current value. Undo restores the previous timeline.
//   {"cmd":"anim.keyframe","object":"ID","frame":F,"offset":[du,dv,dw],"interpolation":"linear|constant|smooth"}
//       Keys the object's FFD parameter offset (parameter units; du moves it along the stroke) at timeline frame F
//       (converted to scene time with the current timeline: (F − start)/fps seconds; F may lie outside the range).
//       "u":du may replace "offset" (v = w = 0). A key at the same time is replaced. interpolation (default linear)
//       shapes the segment that starts at this key. {"cmd":"anim.keyframe","object":"ID","frame":F,"remove":true}
//       deletes the key at F (error when there is none).
//   {"cmd":"anim.clip","object":"ID","path":"file.gltf","clip":"NAME|#i","speed":1,"start_frame":F,"loop":true}
//       Attaches a glTF animation (core::MeshClip: morph targets, skins) to an object loaded from the same file (the
//       vertex counts must agree): the clip poses the rest mesh at every scene time and the FFD warps each pose
//       (two-level animation). clip "" or omitted = the file's first animation; speed > 0 (clip seconds per scene
//       second); start_frame: the timeline frame at which the clip is at its time 0 (default: timeline start).
//       {"cmd":"anim.clip","object":"ID","remove":true} detaches the clip.
// Errors (CommandError, field named): unknown object, object without an FFD (anim.keyframe), non-finite numbers,
// fps/range out of bounds, NaN offsets, no key to remove, clip file without animations ("path"), unknown clip
// ("clip"), vertex count mismatch ("path"), an object with a refined mesh.
#pragma once

#include <optional>
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

struct AnimKeyframeParams {
  std::string object;
  double frame = 0;
  bool remove = false;               // delete the key at `frame` instead
  std::optional<glm::dvec3> offset;  // parameter units
  std::optional<double> u;           // the u offset alone (kept as "u" in the log)
  std::string interpolation = "linear";
  glm::dvec3 key_offset() const { return offset ? *offset : glm::dvec3(u ? *u : 0.0, 0.0, 0.0); }
};

class AnimKeyframeCommand : public ObjectSnapshotCommand<AnimKeyframeCommand, AnimKeyframeParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<AnimKeyframeParams>& schema();

  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

struct AnimClipParams {
  std::string object;
  bool remove = false;  // detach the object's clip instead
  std::string path;     // absolute once parsed
  std::string clip;     // clip name; empty = the file's first
  double speed = 1.0;
  std::optional<double> start_frame;  // default: the timeline's first frame
  bool loop = true;
};

class AnimClipCommand : public ObjectSnapshotCommand<AnimClipCommand, AnimClipParams> {
 public:
  using ObjectSnapshotCommand::ObjectSnapshotCommand;
  static const ParamSchema<AnimClipParams>& schema();

  std::string label() const override;

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string failure_field() const override { return "path"; }
};

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
