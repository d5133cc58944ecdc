#include "ui/dffd_panel.h"
#include "core/commands/codecs.h"
#include "ui/param_widgets.h"

#include <imgui.h>

#include <algorithm>

#include "ui/number_field.h"
#include "ui/placement_panel.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {



// A combo over `names` (#N) choosing `value`; per-item tooltips `tips` (#N or empty). True when changed.
bool string_combo(const char* id, std::string& value, const std::vector<const char*>& names,
                  const std::vector<const char*>& tips) {
  bool changed = false;
  if (ImGui::BeginCombo(id, value.c_str())) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (ImGui::Selectable(names[i], value == names[i]) && value != names[i]) {
        value = names[i];
        changed = true;
      }
      if (!tips.empty()) tooltip(tips[i]);
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool axis_combo(const char* id, int& axis) {
  bool changed = false;
  if (ImGui::BeginCombo(id, core::axis_name(axis))) {
    for (int a = 0; a < 3; ++a)
      if (ImGui::Selectable(core::axis_name(a), a == axis) && a != axis) {
        axis = a;
        changed = true;
      }
    ImGui::EndCombo();
  }
  return changed;
}

constexpr const char* kOpeningTips[] = {
    "left open: the inside is visible (seed section 6.3.2, Fig. 6.10)",
    "stitch: F-/F+ moved to the average level w_s, so the mapped model stays closed (seed section 6.3.2, Fig. 6.7b)",
    "cap: cross-sections triangulated on both sides, so each part is a closed 2-manifold (seed section 6.3.2, "
    "Fig. 6.9)",
};

}  // namespace

double default_kernel_width(const DffdSplitParams& p, const std::vector<DffdObstacleInfo>& candidates) {
  double extent = 0.0;
  const int a = std::clamp(p.axis, 0, 2);
  for (const DffdObstacleInfo& c : candidates)
    if (std::find(p.obstacles.begin(), p.obstacles.end(), c.name) != p.obstacles.end())
      extent = std::max(extent, c.extent[a]);
  return 2.0 * extent;
}

std::string dffd_split_blocked(const std::string& object, const DffdSplitParams& p) {
  if (object.empty()) return "Select the object to split first";
  if (p.obstacles.empty()) return "Tick at least one obstacle the object must split around";
  if (p.axis == p.w_axis) return "The travel axis (u) and the slicing axis (w) must differ";
  return {};
}

nlohmann::json dffd_split_line(const std::string& object, const DffdSplitParams& p,
                               const std::vector<DffdObstacleInfo>& candidates) {
  const double kw = p.kernel_width > 0.0 ? p.kernel_width : default_kernel_width(p, candidates);
  nlohmann::json line = {{"cmd", "dffd.split"},
                         {"object", object},
                         {"obstacles", p.obstacles},
                         {"axis", core::axis_name(p.axis)},
                         {"w_axis", core::axis_name(p.w_axis)},
                         {"order", {p.order[0], p.order[1], p.order[2]}},
                         {"controls", {p.controls[0], p.controls[1], p.controls[2]}},
                         {"kernel", p.kernel},
                         {"kernel_width", kw},
                         {"openings", p.openings},
                         {"fold", p.fold}};
  if (p.margin > 0.0) line["margin"] = p.margin;
  return line;
}

DffdPanelResult draw_dffd_panel(DffdSplitParams& p, const std::string& object,
                                const std::vector<DffdObstacleInfo>& candidates) {
  DffdPanelResult r;
  // Keep ticks only for current candidates, in scene order.
  std::vector<std::string> ticked;
  for (const DffdObstacleInfo& c : candidates)
    if (c.name != object && std::find(p.obstacles.begin(), p.obstacles.end(), c.name) != p.obstacles.end())
      ticked.push_back(c.name);
  p.obstacles = std::move(ticked);

  if (object.empty()) ImGui::TextColored(colors::dim, "Select the object to split.");
  else ImGui::Text("Split %s around:", object.c_str());

  ImGui::TextColored(colors::dim, "Obstacles");
  ImGui::Separator();
  bool any = false;
  for (const DffdObstacleInfo& c : candidates) {
    if (c.name == object) continue;
    any = true;
    bool on = std::find(p.obstacles.begin(), p.obstacles.end(), c.name) != p.obstacles.end();
    if (ImGui::Checkbox(c.name.c_str(), &on)) {
      std::vector<std::string> next;
      for (const DffdObstacleInfo& d : candidates)
        if (d.name == c.name ? on : std::find(p.obstacles.begin(), p.obstacles.end(), d.name) != p.obstacles.end())
          next.push_back(d.name);
      p.obstacles = std::move(next);
    }
    tooltip("A scene object the split object must open around (its bounding box shapes the lattice, seed Fig. 6.4)");
  }
  if (!any) ImGui::TextColored(colors::dim, "(no other visible object)");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Lattice");
  ImGui::Separator();
  row_label("Axis (u)");
  axis_combo("##axis", p.axis);
  tooltip("u: the direction the object travels through the obstacles; 'order' knots are inserted at each\n"
          "obstacle's centre along it (seed section 6.3.1)");
  row_label("W axis (w)");
  axis_combo("##w_axis", p.w_axis);
  tooltip("w: the slicing planes W_k are orthogonal to it; for vertical bars it is their length axis. v is the\n"
          "remaining axis. Must differ from the travel axis");
  if (p.axis == p.w_axis) ImGui::TextColored(colors::error, "axis and w_axis must differ");
  row_label("Order");
  if (ImGui::InputInt3("##order", p.order))
    for (int& o : p.order) o = std::clamp(o, 2, 4);
  tooltip("Order (= degree + 1) of the lattice along u, v, w; 2..4. A discontinuity inserts 'order' knots");
  row_label("Controls");
  if (ImGui::InputInt3("##controls", p.controls))
    for (int a = 0; a < 3; ++a) p.controls[a] = std::clamp(p.controls[a], p.order[a], 256);
  tooltip("Control points l, m, n along u, v, w before knot insertion (each >= its order)");
  for (int a = 0; a < 3; ++a) p.controls[a] = std::max(p.controls[a], p.order[a]);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Opening");
  ImGui::Separator();
  row_label("Kernel");
  string_combo("##kernel", p.kernel, {"gaussian", "bspline"},
               {"kappa: truncated Gaussian falloff of the displacement along u (seed section 6.3.1)",
                "kappa: quadratic B-spline falloff of the displacement along u (seed section 6.3.1)"});
  tooltip("kappa: how the F-/F+ displacement propagates to neighbouring control planes along u");
  const double auto_kw = default_kernel_width(p, candidates);
  double kw = p.kernel_width > 0.0 ? p.kernel_width : auto_kw;
  const double kw_min = 1e-6;
  row_label("Kernel width");
  if (drag_scalar("##kernel_width", ImGuiDataType_Double, &kw, float(std::max(auto_kw, 1.0) * 1e-3), &kw_min,
                        nullptr, p.kernel_width > 0.0 ? "%.4g" : auto_kw > 0.0 ? "%.4g (auto)" : "auto"))
    p.kernel_width = std::max(kw, kw_min);
  tooltip("Support of kappa along u, world units. Auto: 2 x the largest ticked obstacle's extent along the axis");
  if (p.kernel_width > 0.0) {
    if (ImGui::SmallButton("Auto##kw")) p.kernel_width = 0.0;
    tooltip("Back to 2 x the largest obstacle extent along the axis");
  }
  row_label("Openings");
  string_combo("##openings", p.openings, {"open", "stitch", "cap"},
               {kOpeningTips[0], kOpeningTips[1], kOpeningTips[2]});
  tooltip(p.openings == "open" ? kOpeningTips[0] : p.openings == "stitch" ? kOpeningTips[1] : kOpeningTips[2]);
  row_label("Fold-over");
  string_combo("##fold", p.fold, {"reject", "warn"},
               {"reject: a lattice whose u-components are not monotone (det J <= 0 possible, seed Theorem 6) fails "
                "the command",
                "warn: split anyway and report where the fold-over is"});
  tooltip("What a fold-over does (seed Theorem 6: monotone u-components of the control points => det J > 0)");
  row_label("Margin");
  double margin = std::max(p.margin, 0.0);
  const double zero = 0.0;
  if (drag_scalar("##margin", ImGuiDataType_Double, &margin, float(std::max(auto_kw, 1.0) * 1e-3), &zero,
                        nullptr, p.margin > 0.0 ? "%.4g" : "%.4g (default)"))
    p.margin = std::max(margin, 0.0);
  tooltip("World units the lattice extends beyond the obstacles' bounding box (0: the command's default)");

  ImGui::Spacing();
  const std::string blocked = dffd_split_blocked(object, p);
  ImGui::BeginDisabled(!blocked.empty());
  const bool clicked = ImGui::Button("Split", ImVec2(-1, 0));
  ImGui::EndDisabled();
  const ImVec2 mn = ImGui::GetItemRectMin(), mx = ImGui::GetItemRectMax();
  r.button_min = {mn.x, mn.y};
  r.button_max = {mx.x, mx.y};
  tooltip(blocked.empty() ? "Split the object around the ticked obstacles (one undoable dffd.split)" : blocked.c_str());
  if (!blocked.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, colors::dim);
    ImGui::TextWrapped("%s", blocked.c_str());
    ImGui::PopStyleColor();
  }
  if (clicked && blocked.empty()) r.line = dffd_split_line(object, p, candidates);
  return r;
}

}  // namespace trispline::ui
