// trispline::ui DFFD split panel — the parameters of the `dffd.split` command (global discontinuous FFD around
// obstacles, seed §6.3.1, §6.3.2, Fig. 6.1, 6.4, 6.10, 6.11; docs/commands.md) and its "Split" button. Plain data
// in, one command line out: the editor's Split tool executes it.
//   {"cmd":"dffd.split","object":ID,"obstacles":[ID,...],"axis":"x|y|z","w_axis":"x|y|z","order":[o,o,o],
//    "controls":[l,m,n],"kernel":"gaussian|bspline","kernel_width":k,"openings":"open|stitch|cap",
//    "fold":"reject|warn"[,"margin":m]}
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace trispline::ui {

// Mirrors dffd.split's fields. Lattice axes: u = `axis` (the direction the object travels through the obstacles),
// w = `w_axis` (the slicing planes W_k are orthogonal to it), v = the remaining world axis. Orders are degree + 1.
struct DffdSplitParams {
  std::vector<std::string> obstacles;  // ticked obstacle ids, in scene order
  int axis = 0;                        // 0 x, 1 y, 2 z
  int w_axis = 1;                      // must differ from axis
  int order[3] = {3, 3, 3};            // 2..4 per lattice axis (u, v, w)
  int controls[3] = {12, 8, 8};        // control points per lattice axis, each ≥ its order
  std::string kernel = "gaussian";     // κ: "gaussian" (truncated) | "bspline" (quadratic)
  double kernel_width = 0.0;           // world units along u; ≤ 0 = auto (2 × the largest obstacle extent along axis)
  std::string openings = "cap";        // "open" | "stitch" | "cap" (seed §6.3.2)
  std::string fold = "reject";         // "reject" | "warn": a fold-over (seed Theorem 6) fails / only warns
  double margin = 0.0;                 // world units the lattice grows beyond the obstacles; ≤ 0 = omitted
};

// An object that can be ticked as an obstacle: its id and its world bounding-box extent (world units, x y z).
struct DffdObstacleInfo {
  std::string name;
  glm::dvec3 extent{0.0};
};

// 2 × the largest extent along `params.axis` of the ticked obstacles found in `candidates` (world units); 0 if none.
double default_kernel_width(const DffdSplitParams& params, const std::vector<DffdObstacleInfo>& candidates);

// Why the Split button is disabled ("" when a split can be issued): no object, no obstacle ticked, axis = w_axis.
std::string dffd_split_blocked(const std::string& object, const DffdSplitParams& params);

// The dffd.split line for `object` (fields above; kernel_width resolved through default_kernel_width when ≤ 0;
// "margin" only when > 0). Does not check dffd_split_blocked.
nlohmann::json dffd_split_line(const std::string& object, const DffdSplitParams& params,
                               const std::vector<DffdObstacleInfo>& candidates);

struct DffdPanelResult {
  std::optional<nlohmann::json> line;  // the Split button was clicked: the dffd.split line to execute
  glm::vec2 button_min{0.0f}, button_max{0.0f};  // the Split button's screen rectangle (tests click it)
};

// Draws inside the current window, for `object` (the selected object, "" = none) with the other visible objects as
// obstacle `candidates`. Ticks of objects no longer among the candidates are dropped.
DffdPanelResult draw_dffd_panel(DffdSplitParams& params, const std::string& object,
                                const std::vector<DffdObstacleInfo>& candidates);

}  // namespace trispline::ui
