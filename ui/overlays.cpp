#include "ui/overlays.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/base/enum_names.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {
// 20480 → "20,480".
std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}
}  // namespace

std::string ddm_tiles_text(const TimingContext& c) {
  if (c.ddm_instances == 0) return {};
  std::string text = "tiles " + grouped(c.ddm_drawn) + " of " + grouped(c.ddm_instances) + " drawn";
  std::string notes;
  if (c.ddm_keep < 1.0) notes = "moving: 1/" + std::to_string(static_cast<long long>(std::llround(1.0 / c.ddm_keep)));
  if (c.ddm_culled > 0) notes += (notes.empty() ? "culled " : ", culled ") + grouped(c.ddm_culled);
  return notes.empty() ? text : text + " (" + notes + ")";
}

namespace {

constexpr std::size_t kMaxSamples = 2000;
constexpr float kGraphWidth = 300.0f, kGraphHeight = 64.0f;

enum class Pass { frame, ffd, draw, volume, ui };
constexpr Pass kPasses[] = {Pass::frame, Pass::ffd, Pass::draw, Pass::volume, Pass::ui};

ImU32 pass_color(Pass p) {
  switch (p) {
    case Pass::frame:
      return IM_COL32(225, 225, 225, 255);
    case Pass::ffd:
      return IM_COL32(255, 160, 60, 255);
    case Pass::draw:
      return IM_COL32(90, 165, 255, 255);
    case Pass::volume:
      return IM_COL32(200, 130, 255, 255);
    case Pass::ui:
      return IM_COL32(120, 215, 120, 255);
  }
  return IM_COL32_WHITE;
}

const char* pass_name(Pass p) { return core::enum_name(p, {"frame", "FFD eval", "render", "iso ray", "UI"}, ""); }

const char* pass_tooltip(Pass p) {
  switch (p) {
    case Pass::frame:
      return "Frame: CPU wall time from handling events to the buffer swap (includes the GPU passes when they are\n"
             "timed with glFinish). FPS = 1000 / mean time between frames. Means over the last second.";
    case Pass::ffd:
      return "FFD evaluation: time to evaluate the trivariate B-spline at every vertex of the deformed objects with\n"
             "the selected evaluator (GPU timer for GLSL backends, plus CPU time for CPU backends), mean over the\n"
             "frames of the last second that evaluated. Results are cached until the deformation changes.";
    case Pass::draw:
      return "Render: GPU time of drawing the scene (objects, grid, overlays) into the framebuffer.";
    case Pass::volume:
      return "Iso ray: GPU time of the volumes' iso-surfaces, ray cast on the trivariate spline (seed section 7.3)\n"
             "into a layer when the view or a level changed (a preview first when it would take long, refined over\n"
             "the next frames), else only composited. Mean over the last second.";
    case Pass::ui:
      return "UI: GPU time of drawing the Dear ImGui panels (ImGui_ImplOpenGL3_RenderDrawData).";
  }
  return "";
}

double value(const FrameSample& s, Pass p) {
  switch (p) {
    case Pass::frame:
      return s.work_ms;
    case Pass::ffd:
      return s.passes.ffd_ms;
    case Pass::draw:
      return s.passes.draw_ms;
    case Pass::volume:
      return s.passes.volume_ms;
    case Pass::ui:
      return s.passes.ui_ms;
  }
  return -1;
}

// Mean of the non-negative values; negative if none.
struct Mean {
  double sum = 0;
  int n = 0;
  void add(double v) {
    if (v >= 0 && std::isfinite(v)) sum += v, ++n;
  }
  double get() const { return n ? sum / n : -1.0; }
};

void format_ms(char* buf, std::size_t size, double ms) {
  if (ms < 0)
    std::snprintf(buf, size, "-");
  else
    std::snprintf(buf, size, ms < 10 ? "%.2f ms" : ms < 100 ? "%.1f ms" : "%.0f ms", ms);
}

void format_rate(char* buf, std::size_t size, double per_s) {
  if (per_s < 0)
    std::snprintf(buf, size, "-");
  else if (per_s >= 1e9)
    std::snprintf(buf, size, "%.2f G vertices/s", per_s * 1e-9);
  else if (per_s >= 1e6)
    std::snprintf(buf, size, "%.1f M vertices/s", per_s * 1e-6);
  else
    std::snprintf(buf, size, "%.0f k vertices/s", per_s * 1e-3);
}

// The smallest of {1,2,3,4,5,6,8} × 10^k at or above v (the graph's scale).
double nice_ceiling(double v) {
  const double p = std::pow(10.0, std::floor(std::log10(std::max(v, 1e-3))));
  for (double m : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (m * p >= v) return m * p;
  return 10 * p;
}

// A coloured legend square on the current line.
void swatch(ImU32 color) {
  const float h = ImGui::GetTextLineHeight();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + h * 0.2f), ImVec2(p.x + h * 0.6f, p.y + h * 0.8f), color);
  ImGui::Dummy(ImVec2(h * 0.6f, h));
  ImGui::SameLine();
}

// The frame row (FPS, or idle, and the frame time) and one row per pass (FFD eval, render, iso ray with volumes, UI),
// ms, each with its tooltip.
void draw_overlay_pass_rows(const TimingOverlay::Summary& s) {
  char ms[32];
  format_ms(ms, sizeof ms, s.frame_ms);
  swatch(pass_color(Pass::frame));
  if (s.idle || s.fps < 0)
    ImGui::Text("idle          frame %s", ms);
  else
    ImGui::Text("%5.0f FPS     frame %s", s.fps, ms);
  tooltip(s.idle ? "The editor waits for input while nothing changes, so no FPS is shown.\n"
                   "Frame: CPU wall time from handling events to the buffer swap, mean over the last second."
                 : pass_tooltip(Pass::frame));

  for (Pass p : {Pass::ffd, Pass::draw, Pass::volume, Pass::ui}) {
    if (p == Pass::volume && s.volume_ms < 0) continue;  // no volume in the scene
    const double v = p == Pass::ffd      ? s.ffd_ms
                     : p == Pass::draw   ? s.draw_ms
                     : p == Pass::volume ? s.volume_ms
                                         : s.ui_ms;
    format_ms(ms, sizeof ms, v);
    swatch(pass_color(p));
    ImGui::Text("%-9s %10s", pass_name(p), ms);
    tooltip(pass_tooltip(p));
    if (p == Pass::ffd && s.ffd_in_draw) {
      ImGui::SameLine();
      ImGui::TextColored(colors::dim, "+ in render");
      tooltip("The vertex-shader path evaluates the deformation while drawing: its cost is part of 'render'.");
    } else if (p == Pass::ffd && !s.ffd_recent && s.ffd_ms >= 0) {
      ImGui::SameLine();
      ImGui::TextColored(colors::dim, "(last)");
      tooltip(
          "Nothing was evaluated in the last second (results are cached until the deformation changes):\n"
          "these are the figures of the last evaluation.");
    }
  }
}

// FFD throughput (vertices per second, vertices per evaluation), the FFD evaluator in use and the playback clock.
void draw_overlay_ffd_rows(const TimingOverlay::Summary& s, const TimingContext& c) {
  char line[160];
  format_rate(line, sizeof line, s.vertices_per_second);
  ImGui::Text("FFD  %s", line);
  tooltip(s.ffd_in_draw
              ? "FFD throughput of the vertex-shader path: vertices evaluated per second of render time (the\n"
                "evaluation happens while drawing, so this is a lower bound)."
              : "FFD throughput: vertices evaluated per second of FFD evaluation time, over the frames that\n"
                "evaluated (GLSL compute and the CPU paths only evaluate when the deformation changes).");
  if (s.ffd_vertices > 0) {
    ImGui::SameLine();
    ImGui::TextColored(colors::dim, "(%.0f k vertices)", s.ffd_vertices * 1e-3);
    tooltip("Vertices of the deformed objects evaluated per evaluation.");
  }
  ImGui::Text("FFD evaluator: %s", c.ffd_backend.empty() ? "-" : c.ffd_backend.c_str());
  tooltip(
      "The backend that evaluates the deformation (View > FFD evaluator). Nothing visible changes between\n"
      "backends except speed; export and tests always use the CPU reference.");
  if (c.scene_time_s >= 0) {
    ImGui::Text("playback %s t = %.2f s", c.playing ? "on " : "off", c.scene_time_s);
    tooltip(
        "Scene time of animated objects (lattice.animate_offset): each shows F(E(x) + offset + velocity * t).\n"
        "Space (View > Play animation) starts and stops the clock.");
  }
}

// Work beside the frame, each row only when it applies: the live silhouettes' extraction (ms, points), the tile layers
// drawn, the guarantees' computation (ms).
void draw_overlay_live_rows(const TimingContext& c) {
  char ms[32];
  if (c.silhouette_ms >= 0 || c.silhouette_running) {
    format_ms(ms, sizeof ms, c.silhouette_ms);
    ImGui::Text("silhouettes %8s", ms);
    if (c.silhouette_ms >= 0) {
      ImGui::SameLine();
      ImGui::TextColored(colors::dim, "(%zu points%s)", c.silhouette_points, c.silhouette_running ? ", updating" : "");
    }
    tooltip(
        "Silhouettes of the volumes for the current view (seed section 7.3.3): CPU wall time of the last\n"
        "extraction on a worker thread (singleton lookup, Newton steps, polylines, occlusion test). The view\n"
        "stays interactive: a changed view or iso-level is extracted when the last extraction is done.");
  }

  if (const std::string tiles = ddm_tiles_text(c); !tiles.empty()) {
    ImGui::TextUnformatted(tiles.c_str());
    tooltip(
        "Tile layers drawn by GPU instancing: instances left out because they lie outside the view or face\n"
        "away (objects without a deformation), and while the view moves only a share of the rest, so orbiting\n"
        "stays fluid (full detail at rest; replay and recordings always draw every tile).");
  }

  if (c.bounds_ms >= 0 || c.certificate_ms >= 0) {
    format_ms(ms, sizeof ms, std::max(c.bounds_ms, 0.0) + std::max(c.certificate_ms, 0.0));
    ImGui::Text("guarantees  %8s", ms);
    ImGui::SameLine();
    ImGui::TextColored(colors::dim, "(%s)", c.guarantees.c_str());
    tooltip(
        "View > Error bounds and Fold certificate (seed ch. 3): CPU wall time of the last computation for the\n"
        "object shown — per-triangle certified error bounds (with the FFD of its vertices) and the lattice's\n"
        "fold-free certificate. Recomputed only when the lattice changes (every step of a press drag).");
  }
}

// The command on top of the undo stack (none: nothing drawn): its wall time and a table of its stages' CPU times (ms).
void draw_overlay_last_command(const TimingContext& c) {
  if (c.last_command.empty()) return;
  ImGui::Separator();
  char total[32], ms[32];
  format_ms(total, sizeof total, c.last_command_ms);
  ImGui::Text("%s  %s", c.last_command.c_str(), total);
  tooltip(
      "The command on top of the undo stack and its wall time when it last ran (CPU). The rows below are its\n"
      "stages (Command::stats(); the same figures as replay's report.json timings.commands).");
  if (!c.last_stages.empty() &&
      ImGui::BeginTable("##stages", 4, ImGuiTableFlags_SizingFixedFit, ImVec2(kGraphWidth, 0))) {
    for (const StageTiming& st : c.last_stages) {
      ImGui::TableNextColumn();
      ImGui::TextColored(colors::dim, "%s", st.name.c_str());
      tooltip("CPU wall time of this stage of the last command.");
      ImGui::TableNextColumn();
      format_ms(ms, sizeof ms, st.ms);
      ImGui::TextUnformatted(ms);
      tooltip("CPU wall time of this stage of the last command.");
    }
    ImGui::EndTable();
  }
}

}  // namespace

void TimingOverlay::add_frame(const FrameSample& sample) {
  samples_.push_back(sample);
  while (!samples_.empty() &&
         (samples_.size() > kMaxSamples || samples_.front().time_s < sample.time_s - kGraphSeconds))
    samples_.pop_front();
  if (sample.passes.ffd_vertices > 0) {
    last_eval_ = sample;
    has_eval_ = true;
  }
}

TimingOverlay::Summary TimingOverlay::summary() const {
  Summary s;
  if (samples_.empty()) return s;
  const double since = samples_.back().time_s - kAverageSeconds;
  Mean interval, work, draw, ui, ffd, ffd_vertices, volume;
  double rate_vertices = 0, rate_ms = 0;  // evaluating frames with a measured FFD time
  auto add_eval = [&](const FrameSample& f) {
    ffd.add(f.passes.ffd_ms);
    ffd_vertices.add(double(f.passes.ffd_vertices));
    if (ffd_time_ms(f.passes) > 0) {
      rate_vertices += double(f.passes.ffd_vertices);
      rate_ms += ffd_time_ms(f.passes);
    }
    s.ffd_in_draw = f.passes.ffd_in_draw;
  };
  for (auto it = samples_.rbegin(); it != samples_.rend(); ++it) {
    if (s.frames > 0 && it->time_s < since) break;  // the newest frame always counts
    ++s.frames;
    interval.add(it->interval_ms);
    work.add(it->work_ms);
    draw.add(it->passes.draw_ms);
    ui.add(it->passes.ui_ms);
    volume.add(it->passes.volume_ms);
    if (it->passes.ffd_vertices > 0) add_eval(*it);
  }
  s.ffd_recent = ffd_vertices.n > 0;
  if (!s.ffd_recent && has_eval_) add_eval(last_eval_);
  s.frame_ms = work.get();
  s.draw_ms = draw.get();
  s.ui_ms = ui.get();
  s.volume_ms = volume.get();
  s.ffd_ms = ffd.get();
  s.ffd_vertices = std::max(ffd_vertices.get(), 0.0);
  if (rate_ms > 0) s.vertices_per_second = rate_vertices / (rate_ms * 1e-3);
  const double mean_interval = interval.get();
  if (mean_interval > 0) s.fps = 1000.0 / mean_interval;
  // The editor sleeps until input when nothing changes: an FPS figure would then only measure the idle wait.
  s.idle = mean_interval > 100.0 && mean_interval > 4.0 * std::max(s.frame_ms, 0.0);
  return s;
}

void TimingOverlay::draw_graph(float width, float height) const {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 g0 = ImGui::GetCursorScreenPos();
  ImGui::Dummy(ImVec2(width, height));
  const bool hovered = ImGui::IsItemHovered();
  const ImVec2 g1(g0.x + width, g0.y + height);
  dl->AddRectFilled(g0, g1, IM_COL32(0, 0, 0, 90));
  if (samples_.empty()) return;

  double top = 16.7 * 1.1;
  for (const FrameSample& s : samples_)
    for (Pass p : kPasses) top = std::max(top, value(s, p));
  top = nice_ceiling(top);
  const double now = samples_.back().time_s;
  auto x_of = [&](double t) { return g1.x - float((now - t) / kGraphSeconds) * width; };
  auto y_of = [&](double ms) { return g1.y - float(std::min(ms / top, 1.0)) * height; };

  const float y60 = y_of(16.7);
  dl->AddLine(ImVec2(g0.x, y60), ImVec2(g1.x, y60), IM_COL32(255, 255, 255, 60));
  for (Pass p : kPasses) {
    const ImU32 col = pass_color(p);
    for (std::size_t i = 1; i < samples_.size(); ++i) {
      const double a = value(samples_[i - 1], p), b = value(samples_[i], p);
      if (a < 0 || b < 0) continue;  // not measured: a gap
      dl->AddLine(ImVec2(x_of(samples_[i - 1].time_s), y_of(a)), ImVec2(x_of(samples_[i].time_s), y_of(b)), col,
                  p == Pass::frame ? 1.5f : 1.2f);
    }
  }
  char scale[32];
  std::snprintf(scale, sizeof scale, "%g ms", top);
  const float line_h = ImGui::GetTextLineHeight();
  dl->AddText(ImVec2(g1.x - ImGui::CalcTextSize(scale).x - 3, g0.y + 1), IM_COL32(200, 200, 200, 200), scale);
  // "60 FPS" at the left end of its line: above it, or below when the line is near the top.
  dl->AddText(ImVec2(g0.x + 3, y60 - line_h > g0.y + line_h * 0.5f ? y60 - line_h : y60 + 1),
              IM_COL32(200, 200, 200, 140), "60 FPS");

  if (!hovered) return;
  // The frame under the mouse, with its numbers.
  const float mx = ImGui::GetIO().MousePos.x;
  const FrameSample* best = &samples_.back();
  for (const FrameSample& s : samples_)
    if (std::abs(x_of(s.time_s) - mx) < std::abs(x_of(best->time_s) - mx)) best = &s;
  dl->AddLine(ImVec2(x_of(best->time_s), g0.y), ImVec2(x_of(best->time_s), g1.y), IM_COL32(255, 255, 255, 120));
  char f[24], e[24], d[24], v[24], u[24];
  format_ms(f, sizeof f, best->work_ms);
  format_ms(e, sizeof e, best->passes.ffd_ms);
  format_ms(d, sizeof d, best->passes.draw_ms);
  format_ms(v, sizeof v, best->passes.volume_ms);
  format_ms(u, sizeof u, best->passes.ui_ms);
  ImGui::SetTooltip(
      "Last %.0f s, one line per pass (newest on the right; the faint line is 16.7 ms = 60 FPS).\n"
      "%.2f s ago: frame %s, FFD eval %s, render %s, iso ray %s, UI %s",
      kGraphSeconds, now - best->time_s, f, e, d, v, u);
}

bool begin_viewport_overlay(const char* id, float corner_x, float corner_y, float pivot_x, float pivot_y, float alpha) {
  constexpr int flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                        ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                        ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
  ImGui::SetNextWindowPos(ImVec2(corner_x, corner_y), ImGuiCond_Always, ImVec2(pivot_x, pivot_y));
  ImGui::SetNextWindowBgAlpha(alpha);
  ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(18, 18, 20, 255));
  ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(235, 235, 235, 255));
  const bool open = ImGui::Begin(id, nullptr, flags);
  ImGui::PopStyleColor(2);
  if (!open) ImGui::End();
  return open;
}

void TimingOverlay::draw(const Rect& viewport) const {
  // Top-left; readable over a white object as over the dark background.
  if (!begin_viewport_overlay("##timing_overlay", viewport.pos.x + 10, viewport.pos.y + 10, 0.0f, 0.0f, 0.82f)) return;
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + kGraphWidth);
  const Summary s = summary();
  draw_overlay_pass_rows(s);
  draw_overlay_ffd_rows(s, context_);
  draw_overlay_live_rows(context_);
  draw_graph(kGraphWidth, kGraphHeight);

  ImGui::TextColored(colors::dim, "%s", context_.timer_mode.empty() ? "GPU: not timed" : context_.timer_mode.c_str());
  tooltip(
      "How GPU passes are timed. Real GPUs: GL_TIME_ELAPSED queries, read a frame or two later without ever\n"
      "waiting. Software renderers (Mesa llvmpipe): their timer queries return wrong values, so each pass is\n"
      "bracketed by glFinish and timed with the wall clock (this slows the frame a little).");

  draw_overlay_last_command(context_);
  ImGui::PopTextWrapPos();
  ImGui::End();
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
