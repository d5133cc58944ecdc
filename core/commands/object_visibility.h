// `object.visibility` — shows or hides an object or a volume in the viewport and in renders (Blender's hide_viewport
// and hide_render; the Scene panel's eye and camera icons). Fields: declared in object_visibility.cpp (ParamSchema),
// listed in docs/commands.md. `viewport` sets SceneObject::visible / VolumeObject::visible: drawn in the viewport,
// picked by tools and place.sketch's rays, framed by Home (Scene::bounds). `render` sets render_visible: in
// recordings (frames, animation.glb, farm chunks), scene.glb and headless images (render_visible_scene); a volume out
// of renders costs nothing there (no ray casting, no silhouette extraction). Undo restores both flags.
// Errors beyond the declared ranges (CommandError, field named, scene untouched): unknown object or volume (`object`);
// neither field given (`viewport`).
#pragma once

#include "core/commands/declared_command.h"

namespace trispline::core {

struct ObjectVisibilityParams {
  std::string object;
  std::optional<bool> viewport, render;  // unset = unchanged
};

class ObjectVisibilityCommand : public DeclaredCommand<ObjectVisibilityCommand, ObjectVisibilityParams> {
 public:
  static Schema declare();

  void redo(Scene& scene) override;
  void undo(Scene& scene) override;

 private:
  bool viewport_before_ = true, render_before_ = true;  // the flags redo replaced
};

}  // namespace trispline::core
