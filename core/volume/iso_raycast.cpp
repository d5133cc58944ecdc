// Iso-surface ray casting on a VolumeSpline: the CPU reference. See iso_raycast.h.
#include "core/volume/iso_raycast.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
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
  if (brick < 1)
    throw std::invalid_argument("volume range grid: brick must be ≥ 1 index unit, got " + std::to_string(brick));
  VolumeRangeGrid g;
  g.brick = brick;
  const std::array<int, 3>& n = spline.dims();
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(1, (n[a] - 1 + brick - 1) / brick);
  // Per axis, the controls [lo, hi] weighing D on brick b: those of the knot spans meeting the open interval
  // (brick·b, min(brick·(b + 1), n − 1)) — D is continuous, so its values on the closed brick are theirs.
  std::array<std::vector<std::array<int, 2>>, 3> support;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < g.dims[a]; ++b) {
      const double lo = double(brick) * b, hi = std::min(double(brick) * (b + 1), double(n[a] - 1));
      const int first = spline.first_control(spline.span_of(a, lo + 0.25));
      const int last = spline.first_control(spline.span_of(a, hi - 0.25)) + spline.order() - 1;
      support[a].push_back({std::max(first, 0), std::min(last, n[a] - 1)});
    }
  // Per control: value (min and max) and the largest difference to its next neighbour along any axis.
  const std::vector<float>& cp = spline.control_points();
  const std::size_t nx = std::size_t(n[0]), nxy = nx * std::size_t(n[1]);
  std::vector<float> lo(cp), hi(cp), slope(cp.size(), 0.0f);
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const std::size_t k = std::size_t(x) + nx * std::size_t(y) + nxy * std::size_t(z);
        double d = 0.0;  // differences of floats are exact in double; rounded up to float below
        if (x + 1 < n[0]) d = std::max(d, std::abs(double(cp[k + 1]) - cp[k]));
        if (y + 1 < n[1]) d = std::max(d, std::abs(double(cp[k + nx]) - cp[k]));
        if (z + 1 < n[2]) d = std::max(d, std::abs(double(cp[k + nxy]) - cp[k]));
        slope[k] = float(d) < d ? std::nextafter(float(d), std::numeric_limits<float>::infinity()) : float(d);
      }
  // Separable reduction, one axis at a time: extent[a] goes from n[a] controls to dims[a] bricks.
  std::array<int, 3> extent = n;
  for (int axis = 0; axis < 3; ++axis) {
    std::array<int, 3> out_extent = extent;
    out_extent[axis] = g.dims[axis];
    const std::size_t count = std::size_t(out_extent[0]) * out_extent[1] * out_extent[2];
    std::vector<float> lo2(count), hi2(count), slope2(count);
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? std::size_t(extent[0]) : std::size_t(extent[0]) * extent[1];
    std::size_t o = 0;
    for (int c = 0; c < out_extent[2]; ++c)
      for (int b = 0; b < out_extent[1]; ++b)
        for (int a = 0; a < out_extent[0]; ++a, ++o) {
          int p[3] = {a, b, c};
          const std::array<int, 2> range = support[axis][std::size_t(p[axis])];
          p[axis] = range[0];
          std::size_t k =
              std::size_t(p[0]) + std::size_t(extent[0]) * (std::size_t(p[1]) + std::size_t(extent[1]) * p[2]);
          float l = lo[k], h = hi[k], s = slope[k];
          for (int q = range[0] + 1; q <= range[1]; ++q) {
            k += stride;
            l = std::min(l, lo[k]), h = std::max(h, hi[k]), s = std::max(s, slope[k]);
          }
          lo2[o] = l, hi2[o] = h, slope2[o] = s;
        }
    lo.swap(lo2), hi.swap(hi2), slope.swap(slope2);
    extent = out_extent;
  }
  g.range.resize(lo.size());
  for (std::size_t i = 0; i < lo.size(); ++i) g.range[i] = glm::vec2(lo[i], hi[i]);
  g.slope = std::move(slope);
  return g;
}

GridRay clip_ray_to_grid(const VolumeSpline& spline, const glm::dvec3& world_origin, const glm::dvec3& world_dir,
                         double t_max, const char* caller) {
  const std::array<int, 3>& n = spline.dims();
  const glm::dmat4& w2i = spline.world_to_index();
  const glm::dvec3 o = glm::dvec3(w2i * glm::dvec4(world_origin, 1.0));
  const glm::dvec3 d = glm::dmat3(w2i) * world_dir;
  const double len = glm::length(d);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument(std::string(caller) + ": zero ray direction");
  GridRay r;
  r.u = d / len;
  r.index_per_t = len;
  // Clip s (index arc length from o) to the grid box and to t ∈ [0, t_max].
  double s_lo = 0.0, s_hi = t_max * len;
  for (int a = 0; a < 3; ++a) {
    const double hi = n[a] - 1;
    if (r.u[a] == 0.0) {
      if (o[a] < 0.0 || o[a] > hi) return r;
      continue;
    }
    double s0 = (0.0 - o[a]) / r.u[a], s1 = (hi - o[a]) / r.u[a];
    if (s0 > s1) std::swap(s0, s1);
    s_lo = std::max(s_lo, s0);
    s_hi = std::min(s_hi, s1);
  }
  if (!(s_lo <= s_hi)) return r;
  r.inside = true;
  r.entry = o + s_lo * r.u;
  r.length = s_hi - s_lo;
  r.s_entry = s_lo;
  return r;
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
    const std::size_t count = std::size_t(bricks->dims[0]) * bricks->dims[1] * bricks->dims[2];
    for (int a = 0; a < 3; ++a)
      if (bricks->brick < 1 || bricks->dims[a] != std::max(1, (n[a] - 1 + bricks->brick - 1) / bricks->brick) ||
          bricks->range.size() != count || bricks->slope.size() != count)
        throw std::invalid_argument("iso_ray_hit: the range grid was built for another volume size");
  }
  const GridRay ray = clip_ray_to_grid(spline, world_origin, world_dir, t_max, "iso_ray_hit");
  if (!ray.inside) return {};
  const glm::dvec3 entry = ray.entry, u = ray.u;
  const double length = ray.length, s_lo = ray.s_entry, len = ray.index_per_t;
  auto f = [&](double s) { return spline.value(entry + s * u) - iso; };

  // Samples s_m = m·step, m = 0…M−1, and s_M = length. The march keeps the sign of the previous sample m − 1 and its
  // value when it was evaluated (NaN when only its sign is known).
  const std::int64_t last = static_cast<std::int64_t>(std::ceil(length / step_index));
  auto sample_at = [&](std::int64_t m) { return m >= last ? length : double(m) * step_index; };
  const double u_l1 = std::abs(u.x) + std::abs(u.y) + std::abs(u.z);
  std::int64_t m = 0;
  std::int64_t brick_end = bricks ? -1 : last;  // last sample of the current brick whose range holds iso
  double change_per_sample = 0.0;               // bound of |D(s_{m+1}) − D(s_m)| in that brick (0: no bound)
  bool have_prev = false, neg_prev = false;
  double f_prev = std::nan("");
  while (m <= last) {
    double s = sample_at(m), fs = std::nan("");
    bool neg = false;
    std::int64_t next = m + 1;
    if (m > brick_end) {
      // Into the next brick along the ray: its samples m…e.
      const glm::dvec3 p = entry + s * u;
      const std::array<int, 3> b = bricks->brick_of(p);
      const std::size_t bi = bricks->index(b[0], b[1], b[2]);
      const glm::vec2 r = bricks->range[bi];
      double exit = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        if (u[a] > 0.0) exit = std::min(exit, (double(bricks->brick) * (b[a] + 1) - p[a]) / u[a]);
        if (u[a] < 0.0) exit = std::min(exit, (double(bricks->brick) * b[a] - p[a]) / u[a]);
      }
      const std::int64_t e = std::max<std::int64_t>(
          m, static_cast<std::int64_t>(std::min(std::floor((s + std::max(exit, 0.0)) / step_index), double(last))));
      if (double(r.x) > iso || double(r.y) < iso) {
        // D − iso has one sign on the brick: every sample in it has that sign.
        neg = double(r.y) < iso;
        next = e + 1;
      } else {
        brick_end = e;
        change_per_sample = double(bricks->slope[bi]) * u_l1 * step_index;
      }
    }
    if (m <= brick_end) {
      fs = f(s);
      neg = fs < 0.0;
      if (change_per_sample > 0.0) {
        // The next samples whose distance from s_m keeps |D − D(s_m)| below |fs| have fs's sign.
        const double k = std::floor(std::abs(fs) * (1.0 - 1e-9) / change_per_sample);
        if (k >= 1.0) next = std::min(m + 1 + static_cast<std::int64_t>(std::min(k, double(last))), brick_end + 1);
      }
    }
    if (have_prev && neg != neg_prev) {
      // The first sign change: between samples m − 1 and m.
      const double a = sample_at(m - 1);
      if (std::isnan(f_prev)) f_prev = f(a);
      if (std::isnan(fs)) fs = f(s);
      const double sc = refine_crossing(f, a, s, f_prev, fs);
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
    have_prev = true, neg_prev = neg;
    f_prev = next == m + 1 ? fs : std::nan("");  // skipped samples are known by sign only
    m = next;
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
