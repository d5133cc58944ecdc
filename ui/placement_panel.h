// trispline::ui placement panel — the widgets of the Sketch placement tool. It edits place.sketch's own parameters
// (core::PlaceSketchParams, declared once in core/commands/place_sketch.cpp: labels, ranges and tooltips come from
// that declaration) plus the widget state that is not a parameter (the profile curves' control points, the springs
// switch). The tool decides what a committed edit means.
#pragma once

#include <string>
#include <vector>

#include "core/commands/place_sketch.h"
#include "ui/curve_editor.h"

namespace trispline::ui {

// What the panel shows beside the parameters: the profile curves as the user drew them (their samples are
// place.sketch's "width_profile" / "height_profile"), and the springs' values while they are switched off.
struct PlacementPanelState {
  std::vector<CurvePoint> width_curve = flat_curve();   // d(u) factors (seed Eq. 2.5)
  std::vector<CurvePoint> height_curve = flat_curve();  // h(u) factors; a 2-D h(u,v) shows its first row
  core::SpringParams springs;                           // kept while "Relax" is off
  // The state that shows `params` (after a line was adopted from the history).
  static PlacementPanelState from(const core::PlaceSketchParams& params);
};

struct PlacementPanelResult {
  bool object_changed = false;  // the object combo picked another object
  bool committed = false;       // a parameter edit finished (IsItemDeactivatedAfterEdit / combo / checkbox)
  bool reset = false;           // "Defaults" pressed (params already reset)
};

// Draws inside the current window. `params.object` is the name chosen in the combo among `objects`.
PlacementPanelResult draw_placement_panel(core::PlaceSketchParams& params, PlacementPanelState& state,
                                          const std::vector<std::string>& objects);

}  // namespace trispline::ui
