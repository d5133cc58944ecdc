#include "ui/dffd_panel.h"

#include <imgui.h>

#include <algorithm>

#include "core/params/codecs.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {

// A combo over the enumerators of E named `names` (#N), with per-item tooltips `tips` (#N). True when changed.
template <class E>
bool enum_combo(const char* id, E& value, const std::vector<const char*>& names, const std::vector<const char*>& tips) {
  bool changed = false;
  const std::size_t current = static_cast<std::size_t>(value);
  if (ImGui::BeginCombo(id, names.at(current))) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (ImGui::Selectable(names[i], i == current) && i != current) {
        value = static_cast<E>(i);
        changed = true;
      }
      tooltip(tips[i]);
    }
    ImGui::EndCombo();
  }
  return changed;
}

constexpr const char* kOpeningTips[] = {
    "left open: the inside is visible (seed section 6.3.2, Fig. 6.10)",
    "stitch: F-/F+ moved to the average level w_s, so the mapped model stays closed (seed section 6.3.2, Fig. 6.7b)",
    "cap: cross-sections triangulated on both sides, so each part is closed (seed section 6.3.2, Fig. 6.9)",
};

}  // namespace

double default_kernel_width(const core::DffdSplitParams& p, const std::vector<DffdObstacleInfo>& candidates) {
  double extent = 0.0;
  const int a = std::clamp(p.dffd.axis, 0, 2);
  for (const DffdObstacleInfo& c : candidates)
    if (std::find(p.obstacles.begin(), p.obstacles.end(), c.name) != p.obstacles.end())
      extent = std::max(extent, c.extent[a]);
  return 2.0 * extent;
}

std::string dffd_split_blocked(const std::string& object, const core::DffdSplitParams& p) {
  if (object.empty()) return "Select the object to split first";
  if (p.obstacles.empty()) return "Tick at least one obstacle the object must split around";
  if (p.dffd.axis == p.dffd.w_axis) return "The travel axis (u) and the slicing axis (w) must differ";
  return {};
}

nlohmann::json dffd_split_line(const std::string& object, const core::DffdSplitParams& params,
                               const std::vector<DffdObstacleInfo>& candidates) {
  core::DffdSplitParams p = params;
  p.object = object;
  if (!(p.dffd.kernel_width > 0.0)) p.dffd.kernel_width = default_kernel_width(p, candidates);
  if (!(p.dffd.margin > 0.0)) p.dffd.margin = core::GlobalDffdParams{}.margin;
  return core::DffdSplitCommand::schema().to_json(p);
}

DffdPanelResult draw_dffd_panel(core::DffdSplitParams& params, const std::string& object,
                                const std::vector<DffdObstacleInfo>& candidates) {
  const core::ParamSchema<core::GlobalDffdParams>& schema = core::global_dffd_schema();
  core::DffdSplitParams& p = params;
  core::GlobalDffdParams& g = p.dffd;
  DffdPanelResult r;
  // Keep ticks only for current candidates, in scene order.
  std::vector<std::string> ticked;
  for (const DffdObstacleInfo& c : candidates)
    if (c.name != object && std::find(p.obstacles.begin(), p.obstacles.end(), c.name) != p.obstacles.end())
      ticked.push_back(c.name);
  p.obstacles = std::move(ticked);

  if (object.empty())
    ImGui::TextColored(colors::dim, "Select the object to split.");
  else
    ImGui::Text("Split %s around:", object.c_str());

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
    probe::item("dffd.obstacle." + c.name);
    tooltip("A scene object the split object must open around (its bounding box shapes the lattice, seed Fig. 6.4)");
  }
  if (!any) ImGui::TextColored(colors::dim, "(no other visible object)");
  std::string ticked_names;
  for (const std::string& o : p.obstacles) ticked_names += (ticked_names.empty() ? "" : ",") + o;
  probe::value("dffd.obstacles", ticked_names);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Lattice");
  ImGui::Separator();
  param_widget(schema, "axis", g);
  param_widget(schema, "w_axis", g);
  if (g.axis == g.w_axis) ImGui::TextColored(colors::error, "axis and w_axis must differ");
  param_widget(schema, "order", g);
  param_widget(schema, "controls", g);
  for (int a = 0; a < 3; ++a) g.controls[a] = std::max(g.controls[a], g.order[a]);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Opening");
  ImGui::Separator();
  row_label(schema.find("kernel")->label.c_str());
  enum_combo("##kernel", g.kernel, {"gaussian", "bspline"},
             {"kappa: truncated Gaussian falloff of the displacement along u (seed section 6.3.1)",
              "kappa: quadratic B-spline falloff of the displacement along u (seed section 6.3.1)"});
  tooltip(param_tooltip(schema.find("kernel")->doc).c_str());
  const double auto_kw = default_kernel_width(p, candidates);
  double kw = g.kernel_width > 0.0 ? g.kernel_width : auto_kw;
  const double kw_min = 1e-6;
  row_label(schema.find("kernel_width")->label.c_str());
  if (drag_scalar("##kernel_width", ImGuiDataType_Double, &kw, float(std::max(auto_kw, 1.0) * 1e-3), &kw_min, nullptr,
                  g.kernel_width > 0.0 ? "%.4g"
                  : auto_kw > 0.0      ? "%.4g (auto)"
                                       : "auto"))
    g.kernel_width = std::max(kw, kw_min);
  tooltip((param_tooltip(schema.find("kernel_width")->doc) +
           "\nAuto: 2 x the largest ticked obstacle's extent along the axis")
              .c_str());
  if (g.kernel_width > 0.0) {
    if (ImGui::SmallButton("Auto##kw")) g.kernel_width = 0.0;
    tooltip("Back to 2 x the largest obstacle extent along the axis");
  }
  row_label(schema.find("openings")->label.c_str());
  enum_combo("##openings", g.openings, {"open", "stitch", "cap"}, {kOpeningTips[0], kOpeningTips[1], kOpeningTips[2]});
  tooltip(kOpeningTips[static_cast<std::size_t>(g.openings)]);
  param_widget(schema, "fold", g);
  row_label(schema.find("margin")->label.c_str());
  double margin = std::max(g.margin, 0.0);
  const double zero = 0.0;
  if (drag_scalar("##margin", ImGuiDataType_Double, &margin, float(std::max(auto_kw, 1.0) * 1e-3), &zero, nullptr,
                  g.margin > 0.0 ? "%.4g" : "%.4g (default)"))
    g.margin = margin > 0.0 ? margin : core::GlobalDffdParams{}.margin;
  tooltip(param_tooltip(schema.find("margin")->doc).c_str());
  param_widget(schema, "clearance", g);

  ImGui::Spacing();
  const std::string blocked = dffd_split_blocked(object, p);
  ImGui::BeginDisabled(!blocked.empty());
  const bool clicked = ImGui::Button("Split", ImVec2(-1, 0));
  ImGui::EndDisabled();
  probe::item("dffd.split");
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
