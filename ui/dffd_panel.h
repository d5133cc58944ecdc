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

#include "core/commands/dffd_split.h"

namespace trispline::ui {

// An object that can be ticked as an obstacle: its id and its world bounding-box extent (world units, x y z).
struct DffdObstacleInfo {
  std::string name;
  glm::dvec3 extent{0.0};
};

// 2 × the largest extent along `params.axis` of the ticked obstacles found in `candidates` (world units); 0 if none.
double default_kernel_width(const core::DffdSplitParams& params, const std::vector<DffdObstacleInfo>& candidates);

// Why the Split button is disabled ("" when a split can be issued): no object, no obstacle ticked, axis = w_axis.
std::string dffd_split_blocked(const std::string& object, const core::DffdSplitParams& params);

// The dffd.split line of `params` for `object`: the panel's "auto" kernel width (≤ 0) resolved through
// default_kernel_width, a margin ≤ 0 left to the command's default. Does not check dffd_split_blocked.
nlohmann::json dffd_split_line(const std::string& object, const core::DffdSplitParams& params,
                               const std::vector<DffdObstacleInfo>& candidates);

struct DffdPanelResult {
  std::optional<nlohmann::json> line;            // the Split button was clicked: the dffd.split line to execute
  glm::vec2 button_min{0.0f}, button_max{0.0f};  // the Split button's screen rectangle (tests click it)
};

// Draws inside the current window, for `object` (the selected object, "" = none) with the other visible objects as
// obstacle `candidates`. Ticks of objects no longer among the candidates are dropped.
// The panel edits dffd.split's own params (core/commands/dffd_split.h; labels, ranges and tooltips from its
// declaration); a kernel width ≤ 0 means "auto".
DffdPanelResult draw_dffd_panel(core::DffdSplitParams& params, const std::string& object,
                                const std::vector<DffdObstacleInfo>& candidates);

}  // namespace trispline::ui
