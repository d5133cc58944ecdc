#include "core/commands/anim_commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/commands/json_fields.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace jf = json_fields;

const char* interpolation_name(KeyInterpolation k) {
  switch (k) {
    case KeyInterpolation::constant: return "constant";
    case KeyInterpolation::smooth: return "smooth";
    case KeyInterpolation::linear: break;
  }
  return "linear";
}

// ---- anim.timeline ---------------------------------------------------------------------------------------------

CommandPtr AnimTimelineCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<AnimTimelineCommand>();
  if (jf::has(j, "fps")) {
    c->fps_ = jf::get_number(j, "fps");
    // At least one frame per 100 s: below that, frame times overflow long before a timeline ends (1e-320 fps).
    if (!(*c->fps_ >= 0.01 && *c->fps_ <= 240.0))
      throw CommandError("field 'fps': must be in [0.01, 240] frames per second", "fps");
  }
  if (jf::has(j, "start")) {
    c->start_ = jf::get_int(j, "start");
    if (*c->start_ < 0 || *c->start_ > 100000) throw CommandError("field 'start': must be in [0, 100000]", "start");
  }
  if (jf::has(j, "end")) {
    c->end_ = jf::get_int(j, "end");
    if (*c->end_ < 0 || *c->end_ > 100000) throw CommandError("field 'end': must be in [0, 100000]", "end");
  }
  if (!c->fps_ && !c->start_ && !c->end_)
    throw CommandError("field 'fps': give at least one of fps, start, end", "fps");
  return c;
}

nlohmann::json AnimTimelineCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}};
  if (fps_) j["fps"] = *fps_;
  if (start_) j["start"] = *start_;
  if (end_) j["end"] = *end_;
  return j;
}

std::string AnimTimelineCommand::label() const {
  std::string s = "Timeline";
  if (start_ || end_) s += " frames " + (start_ ? std::to_string(*start_) : "…") + "-" + (end_ ? std::to_string(*end_) : "…");
  if (fps_) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " at %g fps", *fps_);
    s += buf;
  }
  return s;
}

void AnimTimelineCommand::redo(Scene& scene) {
  Timeline t = scene.timeline;
  if (fps_) t.fps = *fps_;
  if (start_) t.frame_start = *start_;
  if (end_) t.frame_end = *end_;
  if (t.frame_end < t.frame_start)
    throw CommandError("field 'end': the last frame (" + std::to_string(t.frame_end) +
                           ") is before the first frame (" + std::to_string(t.frame_start) + ")",
                       end_ ? "end" : "start");
  before_ = scene.timeline;
  scene.timeline = t;
}

void AnimTimelineCommand::undo(Scene& scene) { scene.timeline = before_; }

// ---- anim.keyframe ---------------------------------------------------------------------------------------------

CommandPtr AnimKeyframeCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<AnimKeyframeCommand>();
  c->object_ = jf::get_string(j, "object");
  c->frame_ = jf::get_number(j, "frame");
  if (std::abs(c->frame_) > 1e6) throw CommandError("field 'frame': |frame| must be ≤ 1e6", "frame");
  c->remove_ = jf::get_bool(j, "remove", false);
  if (c->remove_) return c;
  if (jf::has(j, "offset")) {
    c->offset_ = jf::get_vec3(j, "offset");
  } else if (jf::has(j, "u")) {
    c->offset_ = {jf::get_number(j, "u"), 0.0, 0.0};
    c->u_only_ = true;
  } else {
    throw CommandError("field 'offset': missing (give \"offset\":[du,dv,dw] or \"u\":du)", "offset");
  }
  for (int a = 0; a < 3; ++a)
    if (std::abs(c->offset_[a]) > 1e6)
      throw CommandError(std::string("field '") + (c->u_only_ ? "u" : "offset") + "': |component| must be ≤ 1e6",
                         c->u_only_ ? "u" : "offset");
  const std::string interp = jf::get_enum(j, "interpolation", {"linear", "constant", "smooth"}, "linear");
  c->interpolation_ = interp == "constant" ? KeyInterpolation::constant
                      : interp == "smooth" ? KeyInterpolation::smooth
                                           : KeyInterpolation::linear;
  return c;
}

nlohmann::json AnimKeyframeCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}, {"frame", frame_}};
  if (remove_) {
    j["remove"] = true;
    return j;
  }
  if (u_only_)
    j["u"] = offset_.x;
  else
    j["offset"] = jf::to_json(offset_);
  j["interpolation"] = interpolation_name(interpolation_);
  return j;
}

std::string AnimKeyframeCommand::label() const {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", frame_);
  return (remove_ ? "Delete keyframe of '" : "Keyframe '") + object_ + "' at frame " + buf;
}

std::optional<SceneObject> AnimKeyframeCommand::build(const Scene& scene) {
  // An FFD object, or a DFFD object (dffd.split): both read their parameter offset at every scene time.
  const SceneObject* found = scene.find(object_);
  SceneObject out = found && found->dffd ? *found : require_deformed_object(scene, object_);
  const double t = scene.timeline.time_of_frame(frame_);
  auto& keys = out.offset_keys;
  // Keys closer than a microsecond are the same key (frames convert through a division).
  auto same = std::find_if(keys.begin(), keys.end(), [&](const OffsetKey& k) { return std::abs(k.time_s - t) < 1e-6; });
  if (remove_) {
    if (same == keys.end())
      throw CommandError("field 'frame': object '" + object_ + "' has no keyframe at frame " +
                             std::to_string(frame_), "frame");
    keys.erase(same);
  } else if (same != keys.end()) {
    same->offset = offset_;
    same->interpolation = interpolation_;
  } else {
    const auto at = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double x, const OffsetKey& k) { return x < k.time_s; });
    keys.insert(at, OffsetKey{t, offset_, interpolation_});
  }
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();  // the t = 0 pose follows the keys
  stats_ = {{"keys", keys.size()}, {"time_s", t},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

// ---- anim.clip -------------------------------------------------------------------------------------------------

CommandPtr AnimClipCommand::parse(const nlohmann::json& j, const CommandContext& ctx) {
  auto c = std::make_unique<AnimClipCommand>();
  c->object_ = jf::get_string(j, "object");
  c->remove_ = jf::get_bool(j, "remove", false);
  if (c->remove_) return c;
  const std::string path = jf::get_string(j, "path");
  if (path.empty()) throw CommandError("field 'path': must not be empty", "path");
  c->path_ = std::filesystem::absolute(ctx.resolve(path)).lexically_normal();
  c->path_logged_ = c->path_.string();
  c->clip_ = jf::get_string(j, "clip", "");
  c->speed_ = jf::get_number(j, "speed", 1.0);
  if (!(c->speed_ > 0.0 && c->speed_ <= 100.0)) throw CommandError("field 'speed': must be in (0, 100]", "speed");
  if (jf::has(j, "start_frame")) {
    c->start_frame_ = jf::get_number(j, "start_frame");
    if (std::abs(*c->start_frame_) > 1e6) throw CommandError("field 'start_frame': |frame| must be ≤ 1e6", "start_frame");
  }
  c->loop_ = jf::get_bool(j, "loop", true);
  return c;
}

nlohmann::json AnimClipCommand::to_json() const {
  nlohmann::json j = {{"cmd", id()}, {"object", object_}};
  if (remove_) {
    j["remove"] = true;
    return j;
  }
  j["path"] = path_logged_;
  j["clip"] = clip_;
  j["speed"] = speed_;
  if (start_frame_) j["start_frame"] = *start_frame_;
  j["loop"] = loop_;
  return j;
}

std::string AnimClipCommand::label() const {
  if (remove_) return "Remove clip from '" + object_ + "'";
  return "Clip '" + (clip_.empty() ? path_.filename().string() : clip_) + "' on '" + object_ + "'";
}

std::optional<SceneObject> AnimClipCommand::build(const Scene& scene) {
  const SceneObject* target = scene.find(object_);
  if (!target) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  if (!remove_) require_no_tile_layers(*target, "a glTF clip");
  SceneObject out = *target;
  if (remove_) {
    if (!target->clip) throw CommandError("field 'object': object '" + object_ + "' has no clip", "object");
    out.clip = nullptr;
    out.refresh();
    return out;
  }
  std::shared_ptr<const MeshClip> clip;
  try {
    clip = MeshClip::load(path_, clip_);
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const bool names_clip = msg.find("clip") != std::string::npos && !clip_.empty();
    throw CommandError(std::string("field '") + (names_clip ? "clip" : "path") + "': " + msg,
                       names_clip ? "clip" : "path");
  } catch (const MeshIoError& e) {
    throw CommandError(std::string("field 'path': ") + e.what(), "path");
  }
  if (clip->vertex_count() != target->rest_mesh->positions.size())
    throw CommandError("field 'path': the clip animates " + std::to_string(clip->vertex_count()) +
                           " vertices but object '" + object_ + "' has " +
                           std::to_string(target->rest_mesh->positions.size()) +
                           " (load the object from the same file, and attach the clip before mesh.refine)",
                       "path");
  auto binding = std::make_shared<ClipBinding>();
  binding->clip = clip;
  binding->speed = speed_;
  binding->start_s = scene.timeline.time_of_frame(start_frame_ ? *start_frame_ : scene.timeline.frame_start);
  binding->loop = loop_;
  out.clip = std::move(binding);
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();
  stats_ = {{"clip", clip->name()},
            {"duration_s", clip->duration_s()},
            {"vertices", clip->vertex_count()},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
