#include "core/commands/anim_clip.h"

#include <chrono>

#include "core/mesh/mesh_io.h"

namespace trispline::core {

auto AnimClipCommand::declare() -> Schema {
  return Schema("anim.clip",
                "Attach a glTF animation clip (morph targets, skin) played before the FFD (two-level animation)")
      .field("object", &P::object, {.required = true, .help = "Object loaded from the same file as the clip"})
      .field("remove", &P::remove, {.write = ParamWrite::UnlessDefault, .help = "Detach the object's clip instead"})
      .stop_if([](const P& p) { return p.remove; })
      .field("path", &P::path, {.required = true, .path = true, .help = "glTF/GLB file holding the clip"})
      .field("clip", &P::clip, {.default_text = "the first", .help = "Name of the clip in the file"})
      .field("speed", &P::speed, {.range = ParamRange{0, 100, true, false}, .help = "Playback speed factor"})
      .field("start_frame", &P::start_frame,
             {.range = ParamRange::magnitude_at_most(1e6),
              .help = "Frame the clip starts at; default: the timeline's first frame"})
      .field("loop", &P::loop, {.help = "Play the clip again after its end"})
      .label([](const P& p) {
        if (p.remove) return "Remove clip from '" + p.object + "'";
        return "Clip '" + (p.clip.empty() ? std::filesystem::path(p.path).filename().string() : p.clip) + "' on '" +
               p.object + "'";
      })
      .failure_field("path");
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
