// Iso-surface ray casting on a VolumeSpline: the CPU reference. See iso_raycast.h.
#include "core/volume/iso_raycast.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace trispline::core {
namespace {

constexpr double kRefineTolerance = 1e-9;  // index units: bracket length at which refinement stops
constexpr int kRefineMaxIterations = 100;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Regula falsi with the Illinois modification on [a, b] (index arc lengths), fa = f(a) and fb = f(b) of opposite
// signs (zero counted positive). Returns the crossing's arc length.
template <class F>
double refine_crossing(const F& f, double a, double b, double fa, double fb) {
  int side = 0;  // which end was kept last: −1 a, +1 b
  for (int it = 0; it < kRefineMaxIterations && b - a > kRefineTolerance; ++it) {
    double c = b - fb * (b - a) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc == 0.0) return c;
    if ((fc < 0.0) == (fa < 0.0)) {
      a = c, fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = c, fb = fc;
      if (side == +1) fa *= 0.5;
      side = +1;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

std::array<int, 3> VolumeRangeGrid::brick_of(const glm::dvec3& x) const {
  std::array<int, 3> b{};
  for (int a = 0; a < 3; ++a) {
    const double q = std::floor(x[a] / brick);
    b[a] = (q > 0.0) ? static_cast<int>(std::min<double>(q, dims[a] - 1)) : 0;  // NaN → 0
  }
  return b;
}

VolumeRangeGrid build_volume_range_grid(const VolumeSpline& spline, int brick) {
  if (brick < 3)
    throw std::invalid_argument("volume range grid: brick must be ≥ 3 index units, got " + std::to_string(brick));
  VolumeRangeGrid g;
  g.brick = brick;
  const std::array<int, 3>& n = spline.dims();
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, (n[a] - 1 + brick - 1) / brick);
  const std::size_t count = std::size_t(g.dims[0]) * std::size_t(g.dims[1]) * std::size_t(g.dims[2]);
  std::vector<glm::vec2> block(
      count, glm::vec2(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()));
  auto idx = [&](int a, int b, int c) {
    return std::size_t(a) + std::size_t(g.dims[0]) * (std::size_t(b) + std::size_t(g.dims[1]) * std::size_t(c));
  };
  // Block (a, b, c) holds control points [brick·a, brick·a + brick − 1] per axis (the last block the rest).
  const std::vector<float>& cp = spline.control_points();
  std::size_t k = 0;
  for (int z = 0; z < n[2]; ++z) {
    const int bz = std::min(z / brick, g.dims[2] - 1);
    for (int y = 0; y < n[1]; ++y) {
      const int by = std::min(y / brick, g.dims[1] - 1);
      for (int x = 0; x < n[0]; ++x, ++k) {
        glm::vec2& r = block[idx(std::min(x / brick, g.dims[0] - 1), by, bz)];
        r.x = std::min(r.x, cp[k]);
        r.y = std::max(r.y, cp[k]);
      }
    }
  }
  // Dilate by one block per axis (separable min / max): the controls weighing D in brick c lie in blocks c−1…c+1.
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<glm::vec2> out(block);
    for (int c = 0; c < g.dims[2]; ++c)
      for (int b = 0; b < g.dims[1]; ++b)
        for (int a = 0; a < g.dims[0]; ++a) {
          const int p[3] = {a, b, c};
          glm::vec2& r = out[idx(a, b, c)];
          for (int d = -1; d <= 1; d += 2) {
            int q[3] = {p[0], p[1], p[2]};
            q[axis] += d;
            if (q[axis] < 0 || q[axis] >= g.dims[axis]) continue;
            const glm::vec2& s = block[idx(q[0], q[1], q[2])];
            r.x = std::min(r.x, s.x);
            r.y = std::max(r.y, s.y);
          }
        }
    block.swap(out);
  }
  g.range = std::move(block);
  return g;
}

IsoHit iso_ray_hit(const VolumeSpline& spline, double iso, const glm::dvec3& world_origin, const glm::dvec3& world_dir,
                   double step_index, double t_max, const VolumeRangeGrid* bricks) {
  if (!finite(world_origin) || !finite(world_dir))
    throw std::invalid_argument("iso_ray_hit: ray origin and direction must be finite");
  if (!std::isfinite(step_index) || !(step_index > 0.0))
    throw std::invalid_argument("iso_ray_hit: step must be finite and > 0, got " + std::to_string(step_index));
  if (std::isnan(t_max) || t_max < 0.0) throw std::invalid_argument("iso_ray_hit: t_max must be ≥ 0");
  const std::array<int, 3>& n = spline.dims();
  if (bricks) {
    for (int a = 0; a < 3; ++a)
      if (bricks->dims[a] != std::max(1, (n[a] - 1 + bricks->brick - 1) / bricks->brick) ||
          bricks->range.size() != std::size_t(bricks->dims[0]) * bricks->dims[1] * bricks->dims[2])
        throw std::invalid_argument("iso_ray_hit: the range grid was built for another volume size");
  }
  const glm::dmat4& w2i = spline.world_to_index();
  const glm::dvec3 o = glm::dvec3(w2i * glm::dvec4(world_origin, 1.0));
  const glm::dvec3 d = glm::dmat3(w2i) * world_dir;
  const double len = glm::length(d);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("iso_ray_hit: zero ray direction");
  const glm::dvec3 u = d / len;

  // Clip s (index arc length from o) to the grid box and to t ∈ [0, t_max].
  double s_lo = 0.0, s_hi = t_max * len;
  for (int a = 0; a < 3; ++a) {
    const double hi = n[a] - 1;
    if (u[a] == 0.0) {
      if (o[a] < 0.0 || o[a] > hi) return {};
      continue;
    }
    double s0 = (0.0 - o[a]) / u[a], s1 = (hi - o[a]) / u[a];
    if (s0 > s1) std::swap(s0, s1);
    s_lo = std::max(s_lo, s0);
    s_hi = std::min(s_hi, s1);
  }
  if (!(s_lo <= s_hi)) return {};
  const glm::dvec3 entry = o + s_lo * u;
  const double length = s_hi - s_lo;
  auto f = [&](double s) { return spline.value(entry + s * u) - iso; };

  // Samples s_m = m·step, m = 0…M−1, and s_M = length.
  const std::int64_t last = static_cast<std::int64_t>(std::ceil(length / step_index));
  auto sample_at = [&](std::int64_t m) { return m >= last ? length : double(m) * step_index; };
  std::int64_t m = 0;
  double s_prev = 0.0, f_prev = f(0.0);
  bool skip_checked = false;  // the current sample's brick was already looked at
  while (m < last) {
    if (bricks && !skip_checked) {
      const glm::dvec3 p = entry + s_prev * u;
      const std::array<int, 3> b = bricks->brick_of(p);
      const glm::vec2 r = bricks->at(b[0], b[1], b[2]);
      if (double(r.x) > iso || double(r.y) < iso) {
        // D − iso keeps its sign up to the brick's exit: jump to the last sample before it.
        double exit = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
          if (u[a] > 0.0) exit = std::min(exit, (double(bricks->brick) * (b[a] + 1) - p[a]) / u[a]);
          if (u[a] < 0.0) exit = std::min(exit, (double(bricks->brick) * b[a] - p[a]) / u[a]);
        }
        const double j = std::min(std::floor((s_prev + std::max(exit, 0.0)) / step_index), double(last));
        skip_checked = true;
        if (j > double(m)) {
          m = static_cast<std::int64_t>(j);
          s_prev = sample_at(m);
          f_prev = f(s_prev);
          continue;
        }
      }
    }
    ++m;
    const double s = sample_at(m);
    const double fs = f(s);
    if ((fs < 0.0) != (f_prev < 0.0)) {
      const double sc = refine_crossing(f, s_prev, s, f_prev, fs);
      IsoHit h;
      h.hit = true;
      h.index_point = entry + sc * u;
      h.world_point = glm::dvec3(spline.index_to_world() * glm::dvec4(h.index_point, 1.0));
      h.t = (s_lo + sc) / len;
      const glm::dvec3 g = spline.world_gradient(spline.jet(h.index_point).gradient);
      const double gl = glm::length(g);
      if (gl > 0.0) h.world_normal = -g / gl;
      return h;
    }
    s_prev = s, f_prev = fs;
    skip_checked = false;
  }
  return {};
}

PixelRay pixel_ray(const glm::dmat4& view, const glm::dmat4& projection, const glm::ivec4& viewport, int x, int y) {
  const glm::dvec2 ndc(2.0 * (x + 0.5 - viewport.x) / viewport.z - 1.0,
                       2.0 * (y + 0.5 - viewport.y) / viewport.w - 1.0);
  const glm::dmat4 inv_proj = glm::inverse(projection);
  glm::dvec4 pn = inv_proj * glm::dvec4(ndc, -1.0, 1.0), pm = inv_proj * glm::dvec4(ndc, 0.0, 1.0);
  pn /= pn.w, pm /= pm.w;
  // In view space both points are near the eye: their difference keeps its precision (the far point would not).
  const glm::dmat4 inv_view = glm::inverse(view);
  return {glm::dvec3(inv_view * glm::dvec4(glm::dvec3(pn), 1.0)), glm::dmat3(inv_view) * glm::dvec3(pm - pn)};
}

IsoHitImage render_iso_hits_cpu(const VolumeSpline& spline, double iso, const glm::dmat4& view,
                                const glm::dmat4& projection, int width, int height, double step_index,
                                const VolumeRangeGrid* bricks) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("render_iso_hits_cpu: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  IsoHitImage img;
  img.width = width, img.height = height;
  img.hits.resize(std::size_t(width) * std::size_t(height));
  img.depth.assign(img.hits.size(), 1.0);
  const glm::dmat4 view_proj = projection * view;
  const glm::ivec4 viewport(0, 0, width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelRay r = pixel_ray(view, projection, viewport, x, y);
      IsoHit h =
          iso_ray_hit(spline, iso, r.origin, r.direction, step_index, std::numeric_limits<double>::infinity(), bricks);
      if (!h.hit) continue;
      const glm::dvec4 clip = view_proj * glm::dvec4(h.world_point, 1.0);
      const double depth = 0.5 * clip.z / clip.w + 0.5;
      if (!(depth <= 1.0)) continue;
      const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
      img.hits[i] = h;
      img.depth[i] = depth;
    }
  return img;
}

}  // namespace trispline::core
