// trispline::ui Scene panel — the objects of a core::Scene (colour swatch, visibility eye, name, vertex count) and its
// volumes (same row, "volume" for the count; the Volume panel, ui/volume_panel.h, shows the selected one),
// selection, the buttons that *request* changes: Load…, Add primitive, Remove, and the selected object's Location /
// Rotation / Scale fields (typed values, one request when a field is left after an edit). The panel never edits the
// scene: it returns a SceneRequest that the editor turns into a command.
#pragma once

#include "core/scene/scene.h"
#include "ui/layout.h"

#include <set>
#include <string>

namespace trispline::ui {

struct SceneRequest {
  enum class Kind { None, Select, ToggleVisible, Load, AddPrimitive, Remove, Frame, Transform };
  Kind kind = Kind::None;
  std::string name;  // object name (Select, ToggleVisible, Remove, Frame, Transform) or primitive kind (AddPrimitive)
  // Transform: the edited row as object.transform's field ("translate", "rotate_deg", "scale") and its new value.
  std::string field = {};
  glm::dvec3 value{0.0};
};

// The transform fields' values while they are edited (kept by the editor across frames): a typed value is only
// requested when the field is left, so the panel must not refresh it from the scene in between.
struct TransformFields {
  std::string object;        // whose values these are
  double values[3][3] = {};  // translate (world units), rotate_deg (degrees), scale
  bool active = false;       // a field has the keyboard
  bool dirty = false;        // edited, not requested yet
  glm::vec2 row_min[3] = {}, row_max[3] = {};  // screen rectangles of the three rows (last drawn; for tests)
};

struct ScenePanelState {
  std::string selected;          // selected object name ("" = none)
  std::set<std::string> hidden;  // objects hidden in the viewport (view state, not a document change)
  bool can_remove = true;        // false when no remove command is registered
  TransformFields* transform = nullptr;  // null: no Transform section
};

// The primitive kinds of the scene.primitive command, in menu order.
inline constexpr const char* kPrimitiveKinds[] = {"teapot", "plane", "sphere", "box", "cylinder", "terrain"};

SceneRequest draw_scene_panel(const Rect& rect, const core::Scene& scene, const ScenePanelState& state);

}  // namespace trispline::ui
