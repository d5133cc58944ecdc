#include "core/commands/object_visibility.h"

#include <tuple>

namespace trispline::core {

namespace {

// Sets the flags of the object or volume `name` (unset = kept) and returns the ones it had. Throws CommandError
// (`object`) when there is neither.
std::pair<bool, bool> set_flags(Scene& scene, const std::string& name, std::optional<bool> viewport,
                                std::optional<bool> render) {
  if (SceneObject* o = scene.find(name)) {
    const std::pair<bool, bool> before{o->visible, o->render_visible};
    o->visible = viewport.value_or(o->visible);
    o->render_visible = render.value_or(o->render_visible);
    return before;
  }
  if (const VolumeObject* v = scene.find_volume(name)) {
    const std::pair<bool, bool> before{v->visible, v->render_visible};
    VolumeObject changed = *v;
    changed.visible = viewport.value_or(v->visible);
    changed.render_visible = render.value_or(v->render_visible);
    scene.replace_volume(std::move(changed));
    return before;
  }
  throw CommandError("field 'object': no object or volume named '" + name + "'", "object");
}

}  // namespace

auto ObjectVisibilityCommand::declare() -> Schema {
  return Schema("object.visibility", "Show or hide an object or a volume in the viewport and in renders")
      .field("object", &P::object, {.required = true, .help = "Object or volume id"})
      .field("viewport", &P::viewport,
             {.default_text = "unchanged",
              .help = "Shown in the viewport, picked by tools, framed by Home (Blender's hide_viewport, inverted)"})
      .field("render", &P::render,
             {.default_text = "unchanged",
              .help = "In recordings, animation.glb, scene.glb and rendered images (Blender's hide_render, inverted)"})
      .check([](P& p) {
        if (!p.viewport && !p.render)
          throw CommandError("field 'viewport': give 'viewport', 'render' or both", "viewport");
      })
      .label([](const P& p) {
        std::string what;
        if (p.viewport) what = *p.viewport ? "Show" : "Hide";
        if (p.render) what += std::string(what.empty() ? "" : ", ") + (*p.render ? "Render" : "Do not render");
        return what + " '" + p.object + "'";
      });
}

void ObjectVisibilityCommand::redo(Scene& scene) {
  std::tie(viewport_before_, render_before_) = set_flags(scene, p_.object, p_.viewport, p_.render);
}

void ObjectVisibilityCommand::undo(Scene& scene) { set_flags(scene, p_.object, viewport_before_, render_before_); }

}  // namespace trispline::core
