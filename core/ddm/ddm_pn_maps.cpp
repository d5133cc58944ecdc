// P/N maps of DDM base surfaces and their CPU evaluation. See ddm_pn_maps.h.
// Sources: seed §5.3.1 (P and N textures of the base surface), §5.3.2 (their bilinear lookup per tile vertex),
// §5.4.1 (UV-space rasterisation, the 8-neighbour diffusion fill and the validity bitmap).
#include "core/ddm/ddm_pn_maps.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace trispline::core {
namespace {

constexpr int kMaxResolution = 4097;
constexpr int F = DdmMaps::kFloatsPerSample;

void check_resolution(glm::ivec2 r) {
  if (r.x < 2 || r.y < 2 || r.x > kMaxResolution || r.y > kMaxResolution)
    throw std::invalid_argument("map_resolution: [" + std::to_string(r.x) + ", " + std::to_string(r.y) +
                                "] samples per chart edge (need 2 … " + std::to_string(kMaxResolution) + ")");
}

void put(float* s, int k, const glm::dvec3& v) {
  s[3 * k] = static_cast<float>(v.x), s[3 * k + 1] = static_cast<float>(v.y), s[3 * k + 2] = static_cast<float>(v.z);
}
glm::dvec3 get(const float* s, int k) { return {s[3 * k], s[3 * k + 1], s[3 * k + 2]}; }

double bbox_diagonal(const DdmMaps& m) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::size_t s = 0; s < m.samples.size(); s += F) {
    const glm::dvec3 p = get(m.samples.data() + s, 0);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const double d = m.samples.empty() ? 0.0 : glm::length(hi - lo);
  return d > 0.0 && std::isfinite(d) ? d : 1.0;
}

// Coordinate of parameter t on an axis of `r` samples: index i ∈ [0, r − 2] and weight f ∈ [0, 1].
void locate(double t, int r, bool periodic, int& i, double& f) {
  t = periodic ? t - std::floor(t) : std::clamp(t, 0.0, 1.0);
  const double x = t * (r - 1);
  i = std::min(static_cast<int>(x), r - 2);
  f = x - i;
}

}  // namespace

DdmMaps ddm_sample_maps(const DdmBase& base, const std::vector<int>& charts, glm::ivec2 resolution,
                        const DdmMaps* previous) {
  check_resolution(resolution);
  DdmMaps maps;
  if (previous) {
    if (previous->resolution != resolution)
      throw std::invalid_argument("map_resolution: the layer's maps have another resolution");
    maps = *previous;
  } else {
    maps.resolution = resolution;
    maps.periodic = base.periodic();
  }
  maps.slot_of_chart.resize(static_cast<std::size_t>(base.chart_count()), -1);
  std::vector<int> fresh;
  for (std::size_t k = 0; k < charts.size(); ++k) {
    const int c = charts[k];
    if (c < 0 || c >= base.chart_count())
      throw std::invalid_argument("base: chart " + std::to_string(c) + " of " + std::to_string(base.chart_count()));
    if (k > 0 && charts[k - 1] >= c) throw std::invalid_argument("base: charts must be sorted and distinct");
    if (maps.slot_of_chart[static_cast<std::size_t>(c)] < 0) fresh.push_back(c);
  }
  const std::size_t per_slot = maps.samples_per_slot() * F;
  if ((maps.chart_of_slot.size() + fresh.size()) * per_slot > (std::size_t{1} << 31))
    throw std::invalid_argument("map_resolution: " + std::to_string(maps.chart_of_slot.size() + fresh.size()) +
                                " charts × " + std::to_string(maps.samples_per_slot()) +
                                " samples exceed 2³¹ floats; lower map_resolution");
  const std::size_t first_slot = maps.chart_of_slot.size();
  for (int c : fresh) {
    maps.slot_of_chart[static_cast<std::size_t>(c)] = static_cast<int>(maps.chart_of_slot.size());
    maps.chart_of_slot.push_back(c);
  }
  maps.samples.resize(maps.chart_of_slot.size() * per_slot);
  if (!maps.valid.empty()) maps.valid.resize(maps.chart_of_slot.size() * maps.samples_per_slot(), 1);
  const int ru = resolution.x, rv = resolution.y;
  tbb::parallel_for(std::size_t{0}, fresh.size(), [&](std::size_t k) {
    const std::size_t slot = first_slot + k;
    for (int j = 0; j < rv; ++j)
      for (int i = 0; i < ru; ++i) {
        const DdmSurfacePoint q =
            base.eval(fresh[k], static_cast<double>(i) / (ru - 1), static_cast<double>(j) / (rv - 1));
        float* s = maps.samples.data() + ((slot * rv + j) * ru + i) * F;
        put(s, 0, q.p), put(s, 1, q.n), put(s, 2, q.du), put(s, 3, q.dv), put(s, 4, q.dn_du), put(s, 5, q.dn_dv);
      }
  });
  maps.base_size = bbox_diagonal(maps);
  return maps;
}

DdmMapsBase::DdmMapsBase(std::shared_ptr<const DdmMaps> maps) : maps_(std::move(maps)) {
  if (!maps_) throw std::invalid_argument("base: no maps");
}

DdmSurfacePoint DdmMapsBase::eval(int chart, double u, double v) const {
  const DdmMaps& m = *maps_;
  if (chart < 0 || chart >= chart_count())
    throw std::out_of_range("base: chart " + std::to_string(chart) + " of " + std::to_string(chart_count()));
  const int slot = m.slot_of_chart[static_cast<std::size_t>(chart)];
  if (slot < 0) throw std::out_of_range("base: chart " + std::to_string(chart) + " was not sampled");
  int i, j;
  double fu, fv;
  locate(u, m.resolution.x, m.periodic.x, i, fu);
  locate(v, m.resolution.y, m.periodic.y, j, fv);
  const float *s00 = m.sample(slot, i, j), *s10 = m.sample(slot, i + 1, j), *s01 = m.sample(slot, i, j + 1),
              *s11 = m.sample(slot, i + 1, j + 1);
  auto lerp = [&](int k) {  // the GLSL path: mix(mix(a, b, fu), mix(c, d, fu), fv)
    const glm::dvec3 a = get(s00, k), b = get(s10, k), c = get(s01, k), d = get(s11, k);
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
  };
  DdmSurfacePoint q;
  q.p = lerp(0);
  const glm::dvec3 n = lerp(1);
  const double len = glm::length(n);
  q.n = len > 0.0 ? n / len : glm::dvec3(0.0, 0.0, 1.0);
  q.du = lerp(2), q.dv = lerp(3), q.dn_du = lerp(4), q.dn_dv = lerp(5);
  return q;
}

namespace {

// The maps' slot of the cell's chart, -1 when the maps hold no such chart.
int chart_slot(const DdmMaps& maps, const DdmInstance& cell) {
  if (cell.chart < 0 || cell.chart >= static_cast<int>(maps.slot_of_chart.size())) return -1;
  return maps.slot_of_chart[static_cast<std::size_t>(cell.chart)];
}

}  // namespace

bool ddm_cell_valid(const DdmMaps& maps, const DdmInstance& cell) {
  const int slot = chart_slot(maps, cell);
  if (slot < 0 || maps.valid.empty()) return slot >= 0;
  const int ru = maps.resolution.x, rv = maps.resolution.y;
  auto range = [](double a, double b, int r, int& lo, int& hi) {
    lo = std::clamp(static_cast<int>(std::floor(std::clamp(a, 0.0, 1.0) * (r - 1))), 0, r - 1);
    hi = std::clamp(static_cast<int>(std::ceil(std::clamp(b, 0.0, 1.0) * (r - 1))), 0, r - 1);
  };
  int i0, i1, j0, j1;
  range(cell.origin.x, cell.origin.x + cell.size.x, ru, i0, i1);
  range(cell.origin.y, cell.origin.y + cell.size.y, rv, j0, j1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if (maps.valid[(static_cast<std::size_t>(slot) * rv + j) * ru + i]) return true;
  return false;
}

bool ddm_cell_centre_valid(const DdmMaps& maps, const DdmInstance& cell) {
  const int slot = chart_slot(maps, cell);
  if (slot < 0 || maps.valid.empty()) return slot >= 0;
  const glm::dvec2 c = cell.origin + 0.5 * cell.size;
  const int i = std::clamp(static_cast<int>(std::lround(std::clamp(c.x, 0.0, 1.0) * (maps.resolution.x - 1))), 0,
                           maps.resolution.x - 1);
  const int j = std::clamp(static_cast<int>(std::lround(std::clamp(c.y, 0.0, 1.0) * (maps.resolution.y - 1))), 0,
                           maps.resolution.y - 1);
  return maps.valid[(static_cast<std::size_t>(slot) * maps.resolution.y + j) * maps.resolution.x + i] != 0;
}

}  // namespace trispline::core

namespace trispline::core {

bool ddm_cell_continuous(const DdmMaps& maps, const DdmInstance& cell) {
  if (cell.chart < 0 || cell.chart >= static_cast<int>(maps.slot_of_chart.size()) ||
      maps.slot_of_chart[static_cast<std::size_t>(cell.chart)] < 0)
    return false;
  const auto maps_ptr = std::shared_ptr<const DdmMaps>(&maps, [](const DdmMaps*) {});  // not owned
  const DdmMapsBase base(maps_ptr);
  constexpr int n = 5;  // n × n points over the cell
  const glm::dvec2 centre = cell.origin + 0.5 * cell.size;
  const DdmSurfacePoint c = base.eval(cell.chart, centre.x, centre.y);
  // The steps the centre's derivatives predict (the atlas has one texel density and low distortion).
  const double step_u = glm::length(c.du) * cell.size.x / (n - 1), step_v = glm::length(c.dv) * cell.size.y / (n - 1);
  glm::dvec3 p[n][n];
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 uv = cell.origin + cell.size * glm::dvec2(i, j) / double(n - 1);
      p[j][i] = base.eval(cell.chart, uv.x, uv.y).p;
    }
  const double slack = 1e-12 * maps.base_size;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n && glm::length(p[j][i + 1] - p[j][i]) > 2.0 * step_u + slack) return false;
      if (j + 1 < n && glm::length(p[j + 1][i] - p[j][i]) > 2.0 * step_v + slack) return false;
    }
  return true;
}

}  // namespace trispline::core
