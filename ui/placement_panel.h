// trispline::ui placement parameters — the widgets of the Sketch placement tool (fields of the place.sketch
// command, see docs/commands.md). Plain data in, flags out: the tool decides what a change means.
#pragma once

#include "core/placement/contact_springs.h"
#include "ui/curve_editor.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace trispline::ui {

// Mirrors place.sketch's parameters. Orders are degree + 1.
struct PlacementParams {
  double width = 0.15;           // half-width d of the band around the stroke, world units at the contact
  double height = 0.2;           // height h of the volume, world units
  int samples[2] = {32, 8};      // contact sampling nu × nv rays
  bool offset_volume = false;    // false: "extrude" (Eq. 2.3), true: "offset" along normals (Eq. 2.4)
  int order[3] = {4, 4, 3};      // ou, ov, ow
  int controls[3] = {10, 4, 3};  // control points per axis, each ≥ its order (u, v ≤ samples)
  int length_axis = 0;           // object axis along the stroke: 0 x, 1 y, 2 z
  int up_axis = 1;               // object axis that points away from the surface
  // Variable width and height along the stroke (seed Eq. 2.5): factors over u ∈ [0,1]; flat = field omitted.
  std::vector<CurvePoint> width_profile = flat_curve();   // d(u) → "width_profile"
  std::vector<CurvePoint> height_profile = flat_curve();  // h(u) → "height_profile"
  // Mass-spring contact surface (seed §2.3.2) → "springs" when on; defaults and ranges of core::SpringParams.
  bool springs_on = false;
  core::SpringParams springs;
  double extent = 1.0;  // fraction of the path the object covers along u, (0,1] → "extent" when < 1
};

// Adds the optional fields above to a place.sketch line (only those that differ from "off"/constant/1).
void add_placement_extras(const PlacementParams& params, nlohmann::json& line);
// Reads them back from a place.sketch line (missing fields: off/constant/1). A 2-D height profile h(u,v) is shown
// by its first row.
void read_placement_extras(const nlohmann::json& line, PlacementParams& params);

const char* axis_name(int axis);  // "x" / "y" / "z"

struct PlacementPanelResult {
  bool object_changed = false;  // the object combo picked another object
  bool committed = false;       // a parameter edit finished (IsItemDeactivatedAfterEdit / combo / checkbox)
  bool reset = false;           // "Defaults" pressed (params already reset)
};

// Draws inside the current window. `object` is the name chosen in the combo among `objects`.
PlacementPanelResult draw_placement_panel(PlacementParams& params, std::string& object,
                                          const std::vector<std::string>& objects);

}  // namespace trispline::ui
