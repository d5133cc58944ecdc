// trispline::ui Inside panel — what an object's cut surfaces look like (`object.inside`, docs/commands.md): the
// inside colour of DFFD caps and incision walls, and an image on the DFFD caps (seed §6.5, Fig. 6.9: a tree split
// open with wood-textured caps) with the world size of one repeat. Plain data in, one command line out: the Split
// (DFFD) tool executes it. The Apply button issues one undoable object.inside; "No texture" removes the image.
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/scene/scene.h"

namespace trispline::ui {

// The fields as edited; taken from the object when another object is shown (synced_object).
struct InsidePanelState {
  std::string synced_object;             // the object the fields were last taken from
  glm::vec3 color{0.62f, 0.10f, 0.08f};  // linear RGB
  std::string texture;                   // image file path as typed ("" = keep the object's)
  double texture_size = 0.25;            // world units per repeat, > 0
};

// The object.inside line of the fields for `object`: color and texture_size always, texture when typed, or
// "no_texture": true when `remove`.
nlohmann::json inside_line(const std::string& object, const InsidePanelState& s, bool remove);

// Draws inside the current window for `object` (null: the section says to select one). Items for GUI tests:
// "inside.color", "inside.texture", "inside.texture_size", "inside.apply", "inside.no_texture"; value
// "inside.current" = the object's texture file ("" = none).
std::optional<nlohmann::json> draw_inside_panel(InsidePanelState& s, const core::SceneObject* object);

}  // namespace trispline::ui
