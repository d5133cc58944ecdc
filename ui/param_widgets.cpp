#include "ui/param_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/base/text.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/theme.h"

namespace trispline::ui {

void row_label(const char* label) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(label);
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
}

void tooltip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

std::string param_tooltip(const core::ParamDoc& doc) {
  std::string tip = doc.help;
  std::string extra = doc.unit;
  if (!doc.range.empty()) extra += (extra.empty() ? "" : ", ") + doc.range;
  if (!extra.empty()) tip += "\n(" + extra + ")";
  return tip;
}

namespace {

// Ranges clamp what a drag can reach; an unbounded side stays open.
template <class T>
void clamp_bounds(const core::ParamRange& r, T* lo, T* hi) {
  const double big = double(std::numeric_limits<T>::max()) / 2;
  *lo = std::isfinite(r.lo) ? T(r.lo) : T(-big);
  *hi = std::isfinite(r.hi) ? T(r.hi) : T(big);
  if constexpr (std::is_floating_point_v<T>) {  // an open bound is never reached
    if (r.lo_open) *lo = std::nextafter(*lo, *hi) + T(1e-6) * std::max(T(1), std::abs(*lo));
    if (r.hi_open) *hi = std::nextafter(*hi, *lo) - T(1e-6) * std::max(T(1), std::abs(*hi));
  } else {
    if (r.lo_open) ++*lo;
    if (r.hi_open) --*hi;
  }
}

}  // namespace

std::string size_param_widget(const ParamWidget& w, const core::ParamFieldInfo& info, double* value, double diagonal,
                              double shown_default, SizeFieldState& state, const std::string& probe) {
  const core::ParamObjectSize& size = *info.object_size;
  const bool object = diagonal > 0.0;
  const double lo = object ? size.min_fraction * diagonal : size.min_fraction > 0.0 ? 1e-3 : 0.0;
  const double hi = object ? size.max_fraction * diagonal : 10.0;
  const double shown = *value > 0.0 ? *value : shown_default;
  const bool limited = !state.limit.empty();
  if (limited) push_limited_frame();
  double typed = shown;
  const float speed = info.ui_relative_step > 0.0 ? float(std::max(shown, 1e-6) * info.ui_relative_step)
                      : w.step > 0.0              ? float(w.step)
                                                  : float(std::max(hi, 1e-3) * 1e-3);
  const std::string& label = w.label.empty() ? w.doc->name : w.label;
  std::string format = w.format.empty() ? "%.4g" : w.format;
  if (!(*value > 0.0)) format += " (auto)";  // follows the object until typed
  const bool changed =
      drag_scalar(label.c_str(), ImGuiDataType_Double, &typed, speed, nullptr, nullptr, format.c_str());
  const bool done = ImGui::IsItemDeactivatedAfterEdit();
  state.committed = done;
  if (limited) pop_limited_frame();
  probe::item(probe);
  probe::value(probe, std::to_string(shown));
  probe::value(probe + ".limited", state.limit);
  if (ImGui::IsItemHovered()) {
    std::string tip = param_tooltip(*w.doc);
    if (size.default_fraction > 0.0)
      tip += "\nDefault: " + short_number(size.default_fraction) + " x the object's bounding-box diagonal";
    if (limited) tip += "\n" + state.limit;
    ImGui::SetTooltip("%s", tip.c_str());
  }
  // While typing each keystroke applies (limited); the reason is given once the edit is done.
  if (changed && std::isfinite(typed)) {
    state.typed = typed;
    *value = std::max(std::clamp(typed, lo, hi), 1e-12);
  }
  if (!done) return {};
  const double kept = std::clamp(state.typed, lo, hi);
  state.limit.clear();
  if (kept == state.typed) return {};
  const std::string name = core::ascii_lower(label);
  char why[240];
  if (kept == lo && size.min_fraction <= 0.0)
    std::snprintf(why, sizeof why, "Limited to 0: the %s is a distance (>= 0)", name.c_str());
  else if (!object)
    std::snprintf(why, sizeof why, "Limited to %.4g: the %s is at most %.4g world units without an object", kept,
                  name.c_str(), hi);
  else
    std::snprintf(why, sizeof why, "Limited to %.4g: the %s is at %s %s x the object's bounding-box diagonal", kept,
                  name.c_str(), kept == hi ? "most" : "least",
                  short_number(kept == hi ? size.max_fraction : size.min_fraction).c_str());
  state.limit = why;
  return state.limit;
}

bool param_widget(const ParamWidget& w, void* value) {
  using core::ParamKind;
  const std::string id = "##" + w.doc->name;
  row_label(w.label.empty() ? w.doc->name.c_str() : w.label.c_str());
  bool committed = false;
  const char* format = w.format.empty() ? nullptr : w.format.c_str();
  switch (w.kind) {
    case ParamKind::Number: {
      double lo, hi;
      clamp_bounds(w.range, &lo, &hi);
      const float step = w.step > 0 ? float(w.step) : 0.01f;
      drag_scalar(id.c_str(), ImGuiDataType_Double, value, step, &lo, &hi, format ? format : "%.3f",
                  ImGuiSliderFlags_AlwaysClamp);
      committed = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case ParamKind::Integer:
    case ParamKind::IVec2:
    case ParamKind::IVec3: {
      int lo, hi;
      clamp_bounds(w.range, &lo, &hi);
      const int n = w.kind == ParamKind::Integer ? 1 : w.kind == ParamKind::IVec2 ? 2 : 3;
      const float step = w.step > 0 ? float(w.step) : 0.1f;
      drag_int_n(id.c_str(), static_cast<int*>(value), n, step, lo, hi, format ? format : "%d",
                 ImGuiSliderFlags_AlwaysClamp);
      committed = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case ParamKind::Vec3: {
      double lo, hi;
      clamp_bounds(w.range, &lo, &hi);
      drag_scalar_n(id.c_str(), ImGuiDataType_Double, value, 3, w.step > 0 ? float(w.step) : 0.01f, &lo, &hi,
                    format ? format : "%.3f", ImGuiSliderFlags_AlwaysClamp);
      committed = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case ParamKind::Bool:
      committed = ImGui::Checkbox(id.c_str(), static_cast<bool*>(value));
      break;
    case ParamKind::Choice: {
      const std::vector<std::string>& choices = *w.choices;
      int index = 0;
      if (w.choice_member == 0) {
        const auto& s = *static_cast<std::string*>(value);
        index = int(std::find(choices.begin(), choices.end(), s) - choices.begin());
      } else if (w.choice_member == 1) {
        index = *static_cast<int*>(value);
      } else {
        index = *static_cast<bool*>(value) ? 1 : 0;
      }
      index = std::clamp(index, 0, int(choices.size()) - 1);
      if (ImGui::BeginCombo(id.c_str(), choices[std::size_t(index)].c_str())) {
        for (std::size_t i = 0; i < choices.size(); ++i) {
          const bool picked = ImGui::Selectable(choices[i].c_str(), int(i) == index);
          probe::item(w.scope + "." + w.doc->name + "." + choices[i]);
          if (picked && int(i) != index) {
            if (w.choice_member == 0)
              *static_cast<std::string*>(value) = choices[i];
            else if (w.choice_member == 1)
              *static_cast<int*>(value) = int(i);
            else
              *static_cast<bool*>(value) = i == 1;
            committed = true;
          }
        }
        ImGui::EndCombo();
      }
      break;
    }
    case ParamKind::String: {
      auto& s = *static_cast<std::string*>(value);
      char buf[256];
      const std::size_t n = std::min(s.size(), sizeof buf - 1);
      std::copy_n(s.data(), n, buf);
      buf[n] = '\0';
      if (ImGui::InputText(id.c_str(), buf, sizeof buf)) s = buf;
      committed = ImGui::IsItemDeactivatedAfterEdit();
      break;
    }
    case ParamKind::Other:
      ImGui::TextDisabled("(edited elsewhere)");
      break;
  }
  probe::item(w.scope + "." + w.doc->name);
  tooltip(param_tooltip(*w.doc).c_str());
  return committed;
}

}  // namespace trispline::ui
