#include "core/commands/anim_commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/mesh/mesh_io.h"

namespace trispline::core {

const char* interpolation_name(KeyInterpolation k) {
  switch (k) {
    case KeyInterpolation::constant:
      return "constant";
    case KeyInterpolation::smooth:
      return "smooth";
    case KeyInterpolation::linear:
      break;
  }
  return "linear";
}

// ---- anim.timeline ---------------------------------------------------------------------------------------------

const ParamSchema<AnimTimelineParams>& AnimTimelineCommand::schema() {
  using P = AnimTimelineParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("anim.timeline", "Set the timeline's frame range and frame rate")
          // At least one frame per 100 s: below that, frame times overflow long before a timeline ends (1e-320 fps).
          .field("fps", &P::fps)
          .range(0.01, 240)
          .unit("frames per second")
          .help("Frame rate")
          .field("start", &P::start)
          .range(0, 100000)
          .help("First frame")
          .field("end", &P::end)
          .range(0, 100000)
          .help("Last frame, ≥ start")
          .check([](const P& p) {
            if (!p.fps && !p.start && !p.end) params::fail("fps", "give at least one of fps, start, end");
          });
  return s;
}

std::string AnimTimelineCommand::label() const {
  std::string s = "Timeline";
  if (p_.start || p_.end)
    s += " frames " + (p_.start ? std::to_string(*p_.start) : "…") + "-" + (p_.end ? std::to_string(*p_.end) : "…");
  if (p_.fps) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " at %g fps", *p_.fps);
    s += buf;
  }
  return s;
}

void AnimTimelineCommand::redo(Scene& scene) {
  Timeline t = scene.timeline;
  if (p_.fps) t.fps = *p_.fps;
  if (p_.start) t.frame_start = *p_.start;
  if (p_.end) t.frame_end = *p_.end;
  if (t.frame_end < t.frame_start)
    throw CommandError("field 'end': the last frame (" + std::to_string(t.frame_end) + ") is before the first frame (" +
                           std::to_string(t.frame_start) + ")",
                       p_.end ? "end" : "start");
  before_ = scene.timeline;
  scene.timeline = t;
}

void AnimTimelineCommand::undo(Scene& scene) { scene.timeline = before_; }

// ---- anim.keyframe ---------------------------------------------------------------------------------------------

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

const ParamSchema<AnimKeyframeParams>& AnimKeyframeCommand::schema() {
  using P = AnimKeyframeParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("anim.keyframe",
                     "Key (or delete a key of) an object's parameter offset along its path at a frame (seed §2.4.3)")
          .field("object", &P::object)
          .required()
          .help("A deformed object (FFD or DFFD)")
          .field("frame", &P::frame)
          .required()
          .magnitude_at_most(1e6)
          .help("Timeline frame (may be fractional)")
          .field("remove", &P::remove)
          .write_unless_default()
          .help("Delete the key at this frame instead")
          .stop_if([](const P& p) { return p.remove; })
          .field("offset", &P::offset)
          .magnitude_at_most(1e6)
          .unit("parameter units")
          .help("Parameter offset [du,dv,dw] at the key (or give \"u\")")
          .field("u", &P::u)
          .magnitude_at_most(1e6)
          .unit("parameter units")
          .help("The u offset alone")
          .check([](P& p) {
            if (p.offset)
              p.u.reset();  // "offset" wins
            else if (!p.u)
              params::fail("offset", "missing (give \"offset\":[du,dv,dw] or \"u\":du)");
          })
          .choice("interpolation", &P::interpolation, {"linear", "constant", "smooth"})
          .help("How the offset goes from this key to the next");
  return s;
}

std::string AnimKeyframeCommand::label() const {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", p_.frame);
  return (p_.remove ? "Delete keyframe of '" : "Keyframe '") + p_.object + "' at frame " + buf;
}

std::optional<SceneObject> AnimKeyframeCommand::build(const Scene& scene) {
  // An FFD object, or a DFFD object (dffd.split): both read their parameter offset at every scene time.
  const SceneObject* found = scene.find(p_.object);
  SceneObject out = found && found->dffd ? *found : require_deformed_object(scene, p_.object);
  const double t = scene.timeline.time_of_frame(p_.frame);
  auto& keys = out.offset_keys;
  // Keys closer than a microsecond are the same key (frames convert through a division).
  auto same = std::find_if(keys.begin(), keys.end(), [&](const OffsetKey& k) { return std::abs(k.time_s - t) < 1e-6; });
  if (p_.remove) {
    if (same == keys.end())
      throw CommandError(
          "field 'frame': object '" + p_.object + "' has no keyframe at frame " + std::to_string(p_.frame), "frame");
    keys.erase(same);
  } else if (same != keys.end()) {
    same->offset = p_.key_offset();
    same->interpolation = interpolation_of(p_.interpolation);
  } else {
    const auto at =
        std::upper_bound(keys.begin(), keys.end(), t, [](double x, const OffsetKey& k) { return x < k.time_s; });
    keys.insert(at, OffsetKey{t, p_.key_offset(), interpolation_of(p_.interpolation)});
  }
  const auto t0 = std::chrono::steady_clock::now();
  out.refresh();  // the t = 0 pose follows the keys
  stats_ = {{"keys", keys.size()},
            {"time_s", t},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

// ---- anim.clip -------------------------------------------------------------------------------------------------

const ParamSchema<AnimClipParams>& AnimClipCommand::schema() {
  using P = AnimClipParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("anim.clip",
                     "Attach a glTF animation clip (morph targets, skin) played before the FFD (two-level animation)")
          .field("object", &P::object)
          .required()
          .help("Object loaded from the same file as the clip")
          .field("remove", &P::remove)
          .write_unless_default()
          .help("Detach the object's clip instead")
          .stop_if([](const P& p) { return p.remove; })
          .field("path", &P::path)
          .required()
          .path()
          .help("glTF/GLB file holding the clip")
          .field("clip", &P::clip)
          .default_text("the first")
          .help("Name of the clip in the file")
          .field("speed", &P::speed)
          .range(0, 100, true, false)
          .help("Playback speed factor")
          .field("start_frame", &P::start_frame)
          .magnitude_at_most(1e6)
          .help("Frame the clip starts at; default: the timeline's first frame")
          .field("loop", &P::loop)
          .help("Play the clip again after its end");
  return s;
}

std::string AnimClipCommand::label() const {
  if (p_.remove) return "Remove clip from '" + p_.object + "'";
  return "Clip '" + (p_.clip.empty() ? std::filesystem::path(p_.path).filename().string() : p_.clip) + "' on '" +
         p_.object + "'";
}

std::optional<SceneObject> AnimClipCommand::build(const Scene& scene) {
  const SceneObject* target = &require_object(scene, p_.object);
  SceneObject out = *target;
  if (p_.remove) {
    if (!target->clip) throw CommandError("field 'object': object '" + p_.object + "' has no clip", "object");
    out.clip = nullptr;
    out.refresh();
    return out;
  }
  std::shared_ptr<const MeshClip> clip;
  try {
    clip = MeshClip::load(p_.path, p_.clip);
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const bool names_clip = msg.find("clip") != std::string::npos && !p_.clip.empty();
    throw CommandError(std::string("field '") + (names_clip ? "clip" : "path") + "': " + msg,
                       names_clip ? "clip" : "path");
  } catch (const MeshIoError& e) {
    throw CommandError(std::string("field 'path': ") + e.what(), "path");
  }
  if (clip->vertex_count() != target->rest_mesh->positions.size())
    throw CommandError("field 'path': the clip animates " + std::to_string(clip->vertex_count()) +
                           " vertices but object '" + p_.object + "' has " +
                           std::to_string(target->rest_mesh->positions.size()) +
                           " (load the object from the same file, and attach the clip before mesh.refine)",
                       "path");
  auto binding = std::make_shared<ClipBinding>();
  binding->clip = clip;
  binding->speed = p_.speed;
  binding->start_s = scene.timeline.time_of_frame(p_.start_frame ? *p_.start_frame : scene.timeline.frame_start);
  binding->loop = p_.loop;
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
