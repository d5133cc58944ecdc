#include "ui/curve_editor.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/theme.h"

namespace trispline::ui {

std::vector<CurvePoint> flat_curve() { return {{0.0, 1.0}, {1.0, 1.0}}; }

bool is_flat(const std::vector<CurvePoint>& points) {
  for (const CurvePoint& p : points)
    if (p.f != 1.0) return false;
  return true;
}

double curve_value(const std::vector<CurvePoint>& pts, double u) {
  if (pts.empty()) return 1.0;
  if (u <= pts.front().u) return pts.front().f;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (u <= pts[i].u) {
      const double span = pts[i].u - pts[i - 1].u;
      if (span <= 0.0) return pts[i].f;
      const double s = (u - pts[i - 1].u) / span;
      return pts[i - 1].f + (pts[i].f - pts[i - 1].f) * s;
    }
  return pts.back().f;
}

void normalise_curve(std::vector<CurvePoint>& pts) {
  for (CurvePoint& p : pts) {
    p.u = std::clamp(std::round((std::isfinite(p.u) ? p.u : 0.0) * kCurveGrid), 0.0, double(kCurveGrid)) / kCurveGrid;
    p.f = std::clamp(std::isfinite(p.f) ? p.f : 1.0, kCurveMinFactor, kCurveMaxFactor);
  }
  std::stable_sort(pts.begin(), pts.end(), [](const CurvePoint& a, const CurvePoint& b) { return a.u < b.u; });
  pts.erase(std::unique(pts.begin(), pts.end(), [](const CurvePoint& a, const CurvePoint& b) { return a.u == b.u; }),
            pts.end());
  if (pts.empty() || pts.front().u != 0.0) pts.insert(pts.begin(), {0.0, pts.empty() ? 1.0 : pts.front().f});
  if (pts.back().u != 1.0) pts.push_back({1.0, pts.back().f});
}

std::vector<double> profile_samples(const std::vector<CurvePoint>& pts) {
  if (is_flat(pts)) return {};
  int k = 1;
  for (; k < kCurveGrid; k *= 2) {
    bool fits = true;
    for (const CurvePoint& p : pts) {
      const double x = p.u * k;
      fits = fits && x == std::round(x);
    }
    if (fits) break;
  }
  std::vector<double> out(k + 1);
  for (int i = 0; i <= k; ++i) out[i] = curve_value(pts, double(i) / k);
  return out;
}

std::vector<CurvePoint> curve_from_samples(const std::vector<double>& samples) {
  if (samples.size() < 2) return flat_curve();
  std::vector<CurvePoint> pts;
  const double k = double(samples.size() - 1);
  for (std::size_t i = 0; i < samples.size(); ++i) pts.push_back({double(i) / k, samples[i]});
  normalise_curve(pts);
  return pts;
}

bool curve_editor(const char* id, std::vector<CurvePoint>& pts, const char* tip, float height) {
  normalise_curve(pts);
  ImGui::PushID(id);
  bool done = false;
  const ImVec2 pos = ImGui::GetCursorScreenPos();
  const ImVec2 size(std::max(ImGui::GetContentRegionAvail().x, 60.0f), height);
  ImGui::InvisibleButton("##plot", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
  const float pad = 6.0f;
  const ImVec2 lo(pos.x + pad, pos.y + pad), hi(pos.x + size.x - pad, pos.y + size.y - pad);
  auto to_px = [&](double u, double f) {
    return ImVec2(lo.x + float(u) * (hi.x - lo.x), hi.y - float(f / kCurveMaxFactor) * (hi.y - lo.y));
  };
  const ImVec2 m = ImGui::GetIO().MousePos;
  const double mu = std::clamp(double(m.x - lo.x) / double(hi.x - lo.x), 0.0, 1.0);
  const double mf =
      std::clamp(double(hi.y - m.y) / double(hi.y - lo.y) * kCurveMaxFactor, kCurveMinFactor, kCurveMaxFactor);

  // The point under the cursor (within 8 px), and the one being dragged (kept in ImGui's state storage).
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID drag_key = ImGui::GetID("##drag");
  int near = -1;
  float best = 8.0f * 8.0f;
  for (int i = 0; i < int(pts.size()); ++i) {
    const ImVec2 q = to_px(pts[i].u, pts[i].f);
    const float d2 = (q.x - m.x) * (q.x - m.x) + (q.y - m.y) * (q.y - m.y);
    if (d2 < best) best = d2, near = i;
  }
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) storage->SetInt(drag_key, near);
  int dragged = storage->GetInt(drag_key, -1);
  if (active && ImGui::IsMouseDown(ImGuiMouseButton_Left) && dragged >= 0 && dragged < int(pts.size())) {
    CurvePoint& p = pts[dragged];
    p.f = std::round(mf * 100.0) / 100.0;                // 0.01 steps: readable numbers in the log
    if (dragged > 0 && dragged + 1 < int(pts.size())) {  // inner points move in u too, between their neighbours
      const double u = std::round(mu * kCurveGrid) / kCurveGrid;
      const double step = 1.0 / kCurveGrid;
      p.u = std::clamp(u, pts[dragged - 1].u + step, pts[dragged + 1].u - step);
    }
  }
  if (dragged >= 0 && ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
    storage->SetInt(drag_key, -1);
    done = true;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && near < 0) {
    const double u = std::round(mu * kCurveGrid) / kCurveGrid;
    bool taken = false;
    for (const CurvePoint& p : pts) taken = taken || p.u == u;
    if (!taken) {
      pts.push_back({u, std::round(mf * 100.0) / 100.0});
      normalise_curve(pts);
      done = true;
    }
  }
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && near > 0 && near + 1 < int(pts.size())) {
    pts.erase(pts.begin() + near);
    done = true;
  }

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(pos, ImVec2(pos.x + size.x, pos.y + size.y), ImGui::GetColorU32(ImGuiCol_FrameBg), 3.0f);
  const ImU32 grid = ImGui::GetColorU32(ImGuiCol_TextDisabled, 0.35f);
  for (int f = 0; f <= 3; ++f) dl->AddLine(to_px(0, f), to_px(1, f), grid);
  for (int q = 0; q <= 4; ++q) dl->AddLine(to_px(q / 4.0, 0), to_px(q / 4.0, kCurveMaxFactor), grid);
  dl->AddLine(to_px(0, 1), to_px(1, 1), ImGui::GetColorU32(ImGuiCol_TextDisabled, 0.8f));  // the constant 1
  for (std::size_t i = 1; i < pts.size(); ++i)
    dl->AddLine(to_px(pts[i - 1].u, pts[i - 1].f), to_px(pts[i].u, pts[i].f), ImGui::GetColorU32(colors::accent), 2.0f);
  for (int i = 0; i < int(pts.size()); ++i) {
    const bool hot = i == dragged || (hovered && i == near);
    dl->AddCircleFilled(to_px(pts[i].u, pts[i].f), hot ? 5.0f : 3.5f,
                        hot ? IM_COL32_WHITE : IM_COL32(200, 200, 200, 255));
  }
  if (hovered || dragged >= 0) {
    const int shown = dragged >= 0 ? dragged : near;
    if (shown >= 0)
      ImGui::SetTooltip("u = %.4g, factor = %.2f\n\n%s", pts[shown].u, pts[shown].f, tip);
    else
      ImGui::SetTooltip(
          "u = %.3f, factor %.2f under the cursor\n%s\n\nDrag a point; double-click adds one, right-click removes "
          "one.\nu runs along the stroke (0 = its start), the factor scales the value (1 = unchanged).",
          mu, mf, tip);
  }
  if (ImGui::SmallButton("Reset")) {
    done = !is_flat(pts) || pts.size() != 2;
    pts = flat_curve();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back to the constant factor 1 (the field is left out of the command)");
  ImGui::PopID();
  return done;
}

}  // namespace trispline::ui
