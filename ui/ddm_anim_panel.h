// trispline::ui tile animation panel — the `ddm.animate` command's fields for one tile layer of the selected object
// (seed §5.4.2: texture-space offset, rotation, scale and w animation, Eq. 5.3: metamorphosis between two tiles of one
// topology) and its "Animate" / "Clear" buttons. Plain data in, one command line out: the Tile Paint tool executes it.
//   {"cmd":"ddm.animate","object":ID,"layer":NAME,"morph_tile":T,"alpha_keys":[[F0,α0],[F1,α1]],
//    "rotate_keys":[[F0,deg0],[F1,deg1]],"scale_keys":…,"w_keys":…,"offset_velocity":[du,dv],
//    "interpolation":"linear|constant|smooth"}
// Widgets are named "ddm_anim.frames", "ddm_anim.turn", "ddm_anim.scale", "ddm_anim.w", "ddm_anim.speed",
// "ddm_anim.animate", "ddm_anim.clear" for GUI tests (ui::probe).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace trispline::ui {

// What the panel shows about a layer (read from core::DdmLayer by the caller).
struct DdmLayerInfo {
  std::string name;
  std::string tile;       // first tile's source ("thorn", a file, …)
  std::size_t tiles = 0;  // instances
  std::size_t vertices = 0;
  bool animated = false;
};

// The panel's values: a metamorphosis, a turn, a scale and a w over two keys, and an offset speed, which
// ddm_animate_line turns into ddm.animate's params (core::DdmAnimateParams).
struct DdmAnimParams {
  std::string morph_tile = "flower";        // generated tile or file; "" = no metamorphosis
  int frame_from = 1, frame_to = 96;        // every keyed value runs from → to between these timeline frames
  double alpha_from = 0.0, alpha_to = 1.0;  // may leave [0, 1] (extrapolation, Eq. 5.3)
  double turn_from = 0.0, turn_to = 0.0;    // degrees added to the layer's rotation; both 0 = no rotate keys
  double scale_from = 1.0, scale_to = 1.0;  // factor on the layer's scale, > 0; both 1 = no scale keys
  double w_from = 1.0, w_to = 1.0;          // factor on the layer's height, > 0; both 1 = no w keys
  double speed_u = 0.0, speed_v = 0.0;      // texture-space offset velocity, chart units per second
  std::string interpolation = "smooth";     // one of ddm.animate's "interpolation" choices (smooth: ease in/out)
};

// Whether the panel keys anything over its frames: a morph tile, a turn, a scale or a w away from rest.
bool ddm_anim_keyed(const DdmAnimParams& p);

// Why Animate is disabled ("" when a line can be issued): no object / layer, frame_from ≥ frame_to with keyed
// values, a scale or w ≤ 0, nothing to animate (nothing keyed and zero speed).
std::string ddm_animate_blocked(const std::string& object, const std::string& layer, const DdmAnimParams& p);

// The ddm.animate line for `layer` of `object` (every key list and offset_velocity always, empty when not used, so
// a second Animate replaces the first): core::DdmAnimateCommand::schema().to_json of the params. {"clear":true} when
// `clear`.
nlohmann::json ddm_animate_line(const std::string& object, const std::string& layer, const DdmAnimParams& p,
                                bool clear = false);

struct DdmAnimPanelResult {
  std::optional<nlohmann::json> line;  // Animate or Clear was clicked
};

// Draws inside the current window: `layer` (chosen among `layers`; reset to the first when not among them), the
// frame range, the morph tile with its α, the turn, scale and w, the offset speed, and the buttons.
DdmAnimPanelResult draw_ddm_anim_panel(DdmAnimParams& params, std::string& layer, const std::string& object,
                                       const std::vector<DdmLayerInfo>& layers);

}  // namespace trispline::ui
