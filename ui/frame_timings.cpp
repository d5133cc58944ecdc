#include "ui/frame_timings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "core/base/enum_names.h"

namespace trispline::ui {

namespace {

// place.sketch's pipeline order (core/commands/place_sketch.cpp); anything else sorts after these by name.
constexpr std::array<std::string_view, 9> kStageOrder = {"bvh",    "fit",   "rays",     "surface", "springs",
                                                         "volume", "embed", "evaluate", "total"};

std::size_t rank(const std::string& name) {
  const auto it = std::find(kStageOrder.begin(), kStageOrder.end(), name);
  return std::size_t(it - kStageOrder.begin());
}

void add(std::vector<StageTiming>& out, const std::string& name, const nlohmann::json& value) {
  if (name.empty() || !value.is_number()) return;
  const double ms = value.get<double>();
  if (std::isfinite(ms)) out.push_back({name, ms});
}

}  // namespace

std::vector<StageTiming> stage_timings(const nlohmann::json& stats) {
  std::vector<StageTiming> out;
  if (!stats.is_object()) return out;
  for (auto it = stats.begin(); it != stats.end(); ++it) {
    const std::string& key = it.key();
    if (key == "ms" && it->is_object()) {
      for (auto s = it->begin(); s != it->end(); ++s) add(out, s.key(), s.value());
    } else if (key.size() > 3 && key.compare(key.size() - 3, 3, "_ms") == 0) {
      add(out, key.substr(0, key.size() - 3), it.value());
    } else if (key.size() > 3 && key.compare(0, 3, "ms_") == 0) {
      add(out, key.substr(3), it.value());
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const StageTiming& a, const StageTiming& b) {
    const std::size_t ra = rank(a.name), rb = rank(b.name);
    return ra != rb ? ra < rb : a.name < b.name;
  });
  return out;
}

double vertices_per_second(std::size_t vertices, double ms) {
  if (vertices == 0 || !(ms > 0)) return -1.0;
  return double(vertices) / (ms * 1e-3);
}

const char* ffd_backend_label(core::FfdBackend b) {
  return core::enum_name(b, {"CPU reference", "CPU fast", "GLSL compute", "GLSL vertex shader"});
}

const char* ffd_backend_tooltip(core::FfdBackend b) {
  switch (b) {
    case core::FfdBackend::glsl_compute:
      return "A GLSL compute shader evaluates the trivariate B-spline at every vertex and writes straight into the\n"
             "vertex buffer the renderer draws (no CPU round trip). Orders 2-4. The default with a GL context.";
    case core::FfdBackend::glsl_vertex:
      return "The vertex shader evaluates the B-spline per vertex while drawing (seed 4.2.1, single phase): nothing\n"
             "is stored, so a parameter offset that changes every frame (animation) costs nothing extra. Orders 2-4.";
    case core::FfdBackend::cpu_fast:
      return "Float evaluation on the CPU, vectorised across vertices, all cores (oneTBB); the mesh is re-uploaded\n"
             "after each evaluation. Orders 2-4.";
    case core::FfdBackend::cpu_ref:
      return "The double-precision CPU reference: the authoritative geometry used for export and tests. Slowest.";
  }
  return "";
}

}  // namespace trispline::ui
