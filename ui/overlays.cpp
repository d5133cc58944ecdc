#include "ui/overlays.h"

#include "ui/theme.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace trispline::ui {

void TimingOverlay::add_frame(double work_ms, double interval_ms) {
  history_[next_] = float(work_ms);
  intervals_[next_] = float(interval_ms);
  next_ = (next_ + 1) % history_.size();
  count_ = std::min(count_ + 1, history_.size());
}

float TimingOverlay::median(const std::array<float, 120>& ring, std::size_t count) {
  if (count == 0) return 0.0f;
  std::array<float, 120> v = ring;  // the first `count` slots are filled until the ring wraps
  std::nth_element(v.begin(), v.begin() + count / 2, v.begin() + count);
  return v[count / 2];
}

void TimingOverlay::draw(const Rect& viewport) const {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  char line[96];
  const double interval = median(intervals_, count_), work = median(history_, count_);
  // The editor sleeps until input when nothing changes: an FPS figure would then only measure the idle wait.
  if (interval > 100.0 && interval > 4.0 * work)
    std::snprintf(line, sizeof line, "idle   frame %.2f ms", work);
  else
    std::snprintf(line, sizeof line, "%.0f FPS   frame %.2f ms", interval > 0 ? 1000.0 / interval : 0.0, work);
  const ImVec2 origin(viewport.pos.x + 10, viewport.pos.y + 10);
  const ImVec2 text_size = ImGui::CalcTextSize(line);
  const float graph_w = 120.0f, graph_h = 28.0f, pad = 6.0f;
  const ImVec2 box_max(origin.x + std::max(text_size.x, graph_w) + 2 * pad, origin.y + text_size.y + graph_h + 3 * pad);
  dl->AddRectFilled(origin, box_max, IM_COL32(20, 20, 22, 170), 4.0f);
  dl->AddText(ImVec2(origin.x + pad, origin.y + pad), IM_COL32(230, 230, 230, 255), line);

  // Frame-time graph: bars scaled to max(33 ms, worst frame); a line marks 16.7 ms (60 FPS).
  if (count_ == 0) return;
  float worst = 33.3f;
  for (std::size_t i = 0; i < count_; ++i) worst = std::max(worst, history_[i]);
  const ImVec2 g0(origin.x + pad, origin.y + 2 * pad + text_size.y);
  const float bar_w = graph_w / float(history_.size());
  for (std::size_t i = 0; i < count_; ++i) {
    const std::size_t idx = (next_ + history_.size() - count_ + i) % history_.size();
    const float h = graph_h * std::min(1.0f, history_[idx] / worst);
    const float x = g0.x + bar_w * float(history_.size() - count_ + i);
    const ImU32 col = history_[idx] > 33.3f ? IM_COL32(230, 110, 100, 220) : IM_COL32(110, 160, 230, 220);
    dl->AddRectFilled(ImVec2(x, g0.y + graph_h - h), ImVec2(x + bar_w, g0.y + graph_h), col);
  }
  const float y60 = g0.y + graph_h * (1.0f - 16.7f / worst);
  dl->AddLine(ImVec2(g0.x, y60), ImVec2(g0.x + graph_w, y60), IM_COL32(255, 255, 255, 80));
}

void draw_working_overlay(const std::string& text) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  dl->AddRectFilled(ImVec2(0, 0), display, IM_COL32(0, 0, 0, 110));
  const ImVec2 ts = ImGui::CalcTextSize(text.c_str());
  const ImVec2 pad(24, 16);
  const ImVec2 c(display.x * 0.5f, display.y * 0.5f);
  const ImVec2 lo(c.x - ts.x * 0.5f - pad.x, c.y - ts.y * 0.5f - pad.y);
  const ImVec2 hi(c.x + ts.x * 0.5f + pad.x, c.y + ts.y * 0.5f + pad.y);
  dl->AddRectFilled(lo, hi, ImGui::GetColorU32(ImGuiCol_PopupBg), 6.0f);
  dl->AddRect(lo, hi, ImGui::ColorConvertFloat4ToU32(colors::accent), 6.0f, 0, 1.5f);
  dl->AddText(ImVec2(lo.x + pad.x, lo.y + pad.y), ImGui::GetColorU32(ImGuiCol_Text), text.c_str());
}

}  // namespace trispline::ui
