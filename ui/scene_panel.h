// trispline::ui Scene panel — the objects of a core::Scene (colour swatch, visibility eye, name, vertex count),
// selection, and the buttons that *request* changes: Load…, Add primitive, Remove. The panel never edits the
// scene: it returns a SceneRequest that the editor turns into a command.
#pragma once

#include "core/scene/scene.h"
#include "ui/layout.h"

#include <set>
#include <string>

namespace trispline::ui {

struct SceneRequest {
  enum class Kind { None, Select, ToggleVisible, Load, AddPrimitive, Remove, Frame };
  Kind kind = Kind::None;
  std::string name;  // object name (Select, ToggleVisible, Remove, Frame) or primitive kind (AddPrimitive)
};

struct ScenePanelState {
  std::string selected;          // selected object name ("" = none)
  std::set<std::string> hidden;  // objects hidden in the viewport (view state, not a document change)
  bool can_remove = true;        // false when no remove command is registered
};

// The primitive kinds of the scene.primitive command, in menu order.
inline constexpr const char* kPrimitiveKinds[] = {"teapot", "plane", "sphere", "box", "cylinder", "terrain"};

SceneRequest draw_scene_panel(const Rect& rect, const core::Scene& scene, const ScenePanelState& state);

}  // namespace trispline::ui
