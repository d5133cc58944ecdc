// trispline::ui Scene panel — the objects of a core::Scene (viewport eye, render camera, colour swatch, name, vertex
// count) and its volumes (same row, "volume" for the count; the Volume panel, ui/volume_panel.h, shows the selected
// one), selection, the buttons that *request* changes: Load…, Add (a primitive, or Text… through a dialog whose
// fields are scene.text's), Remove, and the selected object's Location
// / Rotation / Scale fields (typed values, one request when a field is left after an edit). The panel never edits the
// scene: it returns a SceneRequest that the editor turns into a command.
#pragma once

#include <string>

#include "core/commands/scene_text.h"
#include "core/scene/scene.h"
#include "ui/layout.h"

namespace trispline::ui {

struct SceneRequest {
  // ToggleVisible / ToggleRender: the eye / camera icon was clicked (object.visibility with the flag flipped).
  enum class Kind { None, Select, ToggleVisible, ToggleRender, Load, AddPrimitive, AddText, Remove, Frame, Transform };
  Kind kind = Kind::None;
  std::string name;  // object or volume name, or the primitive kind (AddPrimitive)
  // Transform: the edited row as object.transform's field ("translate", "rotate_deg", "scale") and its new value.
  std::string field = {};
  glm::dvec3 value{0.0};
};

// The transform fields' values while they are edited (kept by the editor across frames): a typed value is only
// requested when the field is left, so the panel must not refresh it from the scene in between.
struct TransformFields {
  std::string object;                          // whose values these are
  double values[3][3] = {};                    // translate (world units), rotate_deg (degrees), scale
  bool active = false;                         // a field has the keyboard
  bool dirty = false;                          // edited, not requested yet
  glm::vec2 row_min[3] = {}, row_max[3] = {};  // screen rectangles of the three rows (last drawn; for tests)
};

struct ScenePanelState {
  std::string selected;                  // selected object name ("" = none)
  bool can_remove = true;                // false when no remove command is registered
  TransformFields* transform = nullptr;  // null: no Transform section
  // The Add ▸ Text… dialog's fields (kept by the editor; AddText asks to run scene.text with them); null: no Text item.
  core::SceneTextParams* text = nullptr;
};

// The primitive kinds of the scene.primitive command, in menu order.
inline constexpr const char* kPrimitiveKinds[] = {"teapot", "plane", "sphere", "box", "cylinder", "terrain"};

SceneRequest draw_scene_panel(const Rect& rect, const core::Scene& scene, const ScenePanelState& state);

}  // namespace trispline::ui
