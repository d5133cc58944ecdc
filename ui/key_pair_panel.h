// trispline::ui two-key animation panel — a value keyed at two timeline frames with an easing, and "Animate" /
// "Clear" buttons: the Incision tool's opening over time (incision.animate "opening_keys") and the Split tool's seam
// over time (dffd.animate "stitch_keys"). Plain data in, what was clicked out; the tool writes the command line.
// Widgets are named "<id>.frame_from", "<id>.frame_to", "<id>.value_from", "<id>.value_to", "<id>.animate",
// "<id>.clear" for GUI tests (ui::probe).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace trispline::ui {

struct KeyPairParams {
  int frame_from = 1, frame_to = 24;        // timeline frames of the two keys
  double value_from = 0.0, value_to = 1.0;  // the keyed value there (any real: outside [0, 1] extrapolates)
  std::string interpolation = "smooth";     // linear | constant | smooth (Blender's keyframe interpolation)
};

// What the panel says about its value (labels and tooltips; the tool's words).
struct KeyPairSpec {
  const char* id;             // probe scope, e.g. "incision_anim"
  const char* value_label;    // "Opening"
  const char* value_tooltip;  // what 0 and 1 mean
  const char* animate_tooltip;
  const char* clear_tooltip;
};

// Why Animate is disabled ("" when a line can be issued): `unavailable` (the tool's reason, e.g. no object) first,
// then frame_from ≥ frame_to.
std::string key_pair_blocked(const KeyPairParams& p, const std::string& unavailable);

// The two [frame, value] keys of `p`, in the order of the command's key lists.
std::vector<glm::dvec2> key_pair_keys(const KeyPairParams& p);

struct KeyPairResult {
  bool animate = false;  // Animate clicked (never when blocked)
  bool clear = false;    // Clear clicked (never when `can_clear` is false)
};

// Draws inside the current window: frames, values, easing, Animate and Clear. `unavailable` disables Animate with
// that reason as its tooltip; `can_clear` enables Clear (the object has keys to remove).
KeyPairResult draw_key_pair_panel(KeyPairParams& p, const KeyPairSpec& spec, const std::string& unavailable,
                                  bool can_clear);

}  // namespace trispline::ui
