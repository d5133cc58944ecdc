#include "ui/param_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ui/gui_probe.h"
#include "ui/number_field.h"

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
