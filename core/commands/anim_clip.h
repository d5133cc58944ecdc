// Animation commands (seed §2.4.3: objects walking along the sketched path; two-level animation with a glTF clip).
//
//   {"cmd":"anim.clip","object":"ID","path":"file.gltf","clip":"NAME|#i","speed":1,"start_frame":F,"loop":true}
//       Attaches a glTF animation (core::MeshClip: morph targets, skins) to an object loaded from the same file (the
//       vertex counts must agree): the clip poses the rest mesh at every scene time and the FFD warps each pose
//       (two-level animation). clip "" or omitted = the file's first animation; speed > 0 (clip seconds per scene
//       second); start_frame: the timeline frame at which the clip is at its time 0 (default: timeline start).
//       {"cmd":"anim.clip","object":"ID","remove":true} detaches the clip.
// Errors (CommandError, field named): unknown object, clip file without animations ("path"), unknown clip ("clip"),
// vertex count mismatch ("path"), an object with a refined mesh.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

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

}  // namespace trispline::core
