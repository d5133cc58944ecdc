// trispline::ui frame timings — the plain data behind the live timing overlay (ui/overlays.h) and replay's
// report.json "timings" object (editor/replay/replay.cpp), so both show the same numbers.
//   StageTiming, stage_timings()   a command's CPU time per stage, from its Command::stats() JSON
//   PassTimings                    one frame's GPU passes: FFD evaluation, scene draw, iso ray casting, UI (ms;
//                                  < 0 = unknown)
//   vertices_per_second()          FFD throughput
//   ffd_backend_label/_tooltip()   the names the FFD evaluator setting shows
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"

namespace trispline::ui {

struct StageTiming {
  std::string name;  // "fit", "rays", ... (the stats key without "_ms" / "ms_")
  double ms = 0;     // CPU wall clock, milliseconds
};

// The stage timings in a command's stats() JSON: every number of a nested "ms" object, every top-level number whose
// key ends in "_ms" or starts with "ms_" (place.sketch: bvh, fit, rays, surface, volume, embed, evaluate). Known
// stages come in pipeline order, others after them by name. Non-numeric entries are ignored; never throws.
std::vector<StageTiming> stage_timings(const nlohmann::json& stats);

// GPU passes of one frame, milliseconds (GpuTimer results: GL_TIME_ELAPSED, or glFinish + wall clock on a software
// renderer); negative = not measured (yet).
struct PassTimings {
  double ffd_ms = -1;            // FFD evaluation of the deformed objects (RenderStats::ffd_ms)
  double draw_ms = -1;           // scene rendering (RenderStats::draw_ms)
  double ui_ms = -1;             // ImGui's render pass
  double volume_ms = -1;         // the volumes' iso-surface pass (RenderStats::volume_ms; -1 without volumes)
  std::size_t ffd_vertices = 0;  // vertices evaluated this frame (RenderStats::ffd_vertices)
  // The GLSL vertex-shader path evaluates while drawing: its FFD time is part of draw_ms (ffd_ms only covers the
  // preparation), so its throughput is measured against draw_ms (a lower bound).
  bool ffd_in_draw = false;
};

// vertices per second of `ms`; negative when ms <= 0 or vertices == 0.
double vertices_per_second(std::size_t vertices, double ms);
// The FFD time behind `p.ffd_vertices`: draw_ms when ffd_in_draw, else ffd_ms (negative = unknown).
inline double ffd_time_ms(const PassTimings& p) { return p.ffd_in_draw ? p.draw_ms : p.ffd_ms; }

// "GLSL compute", "GLSL vertex shader", "CPU fast", "CPU reference".
const char* ffd_backend_label(core::FfdBackend backend);
// One or two sentences for the setting's tooltip.
const char* ffd_backend_tooltip(core::FfdBackend backend);
// The order the setting lists them in (fastest first).
inline constexpr core::FfdBackend kFfdBackendsShown[] = {core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex,
                                                         core::FfdBackend::cpu_fast, core::FfdBackend::cpu_ref};

}  // namespace trispline::ui
