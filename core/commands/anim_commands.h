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

#include "core/commands/snapshot_command.h"

namespace trispline::core {

class AnimTimelineCommand : public Command {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "anim.timeline"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  std::optional<double> fps_;
  std::optional<int> start_, end_;
  Timeline before_;
};

class AnimKeyframeCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "anim.keyframe"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::string object_;
  double frame_ = 0;
  glm::dvec3 offset_{0.0};
  bool u_only_ = false;  // logged as "u"
  KeyInterpolation interpolation_ = KeyInterpolation::linear;
  bool remove_ = false;
  nlohmann::json stats_ = nlohmann::json::object();
};

class AnimClipCommand : public SnapshotCommand {
 public:
  static CommandPtr parse(const nlohmann::json& j, const CommandContext& ctx);
  std::string id() const override { return "anim.clip"; }
  nlohmann::json to_json() const override;
  std::string label() const override;
  nlohmann::json stats() const override { return stats_; }

 protected:
  std::string target() const override { return object_; }
  std::optional<SceneObject> build(const Scene& scene) override;
  std::string failure_field() const override { return "path"; }

 private:
  std::string object_, path_logged_, clip_;
  std::filesystem::path path_;
  double speed_ = 1.0;
  std::optional<double> start_frame_;
  bool loop_ = true, remove_ = false;
  nlohmann::json stats_ = nlohmann::json::object();
};

// "linear" | "constant" | "smooth".
const char* interpolation_name(KeyInterpolation k);

}  // namespace trispline::core
