// `anim.clip` — attaches a glTF animation (core::MeshClip: morph targets, skins) to an object loaded from the same
// file, or detaches it (seed §2.4.3: two-level animation with a glTF clip). Fields: declared in anim_clip.cpp
// (ParamSchema), listed in docs/commands.md. The vertex counts must agree: the clip poses the rest mesh at every scene
// time and the FFD warps each pose (two-level animation). `clip` names the clip, or gives its index as "#i"; speed is
// clip seconds per scene second; start_frame is the timeline frame at which the clip is at its time 0.
// Errors beyond the declared ranges (CommandError, field named): unknown object, a clip to remove that the object does
// not have ("object"); clip file without animations ("path"), unknown clip ("clip"), vertex count mismatch, e.g. an
// object with a refined mesh ("path").
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

struct AnimClipCommand : ObjectSnapshotCommand<AnimClipCommand, AnimClipParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
