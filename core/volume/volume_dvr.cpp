// Direct volume rendering, CPU reference. See volume_dvr.h. Source: seed §7.4 (Fig. 7.7); emission–absorption and
// opacity correction: Engel et al. 2006, "Real-Time Volume Graphics" §1.4, §1.4.3.
#include "core/volume/volume_dvr.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trispline::core {
namespace {

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace

glm::dvec4 TransferFunction::at(double v) const {
  if (points.empty()) return glm::dvec4(0.0);
  if (!(v > points.front().value)) return points.front().rgba;  // NaN too
  if (v >= points.back().value) return points.back().rgba;
  const auto hi =
      std::upper_bound(points.begin(), points.end(), v, [](double x, const TransferPoint& p) { return x < p.value; });
  const auto lo = hi - 1;
  const double f = (v - lo->value) / (hi->value - lo->value);
  return lo->rgba + f * (hi->rgba - lo->rgba);
}

double TransferFunction::max_opacity(double lo, double hi) const {
  double m = std::max(at(lo).w, at(hi).w);
  for (const TransferPoint& p : points)
    if (p.value > lo && p.value < hi) m = std::max(m, p.rgba.w);
  return m;
}

bool TransferFunction::operator==(const TransferFunction& o) const {
  if (points.size() != o.points.size()) return false;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].value != o.points[i].value || points[i].rgba != o.points[i].rgba) return false;
  return true;
}

std::string transfer_function_error(const TransferFunction& tf) {
  const std::size_t n = tf.points.size();
  if (n < 2 || n > std::size_t(kMaxTransferPoints))
    return "needs 2 to " + std::to_string(kMaxTransferPoints) + " points [value, r, g, b, a], got " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) {
    const TransferPoint& p = tf.points[i];
    const std::string at = "point " + std::to_string(i) + ": ";
    if (!std::isfinite(p.value)) return at + "value must be finite";
    if (i > 0 && !(p.value > tf.points[i - 1].value)) return at + "values must increase from point to point";
    for (int c = 0; c < 4; ++c)
      if (!(p.rgba[c] >= 0.0 && p.rgba[c] <= 1.0)) return at + "r, g, b and a must lie in [0, 1]";
  }
  return {};
}

TransferFunction ct_transfer_function() {
  return {{{-1000.0, {0.0, 0.0, 0.0, 0.0}},
           {-600.0, {0.0, 0.0, 0.0, 0.0}},
           {-400.0, {0.90, 0.55, 0.40, 0.012}},
           {100.0, {0.85, 0.45, 0.35, 0.02}},
           {250.0, {0.95, 0.90, 0.80, 0.0}},
           {400.0, {1.0, 0.96, 0.86, 0.6}},
           {2000.0, {1.0, 1.0, 1.0, 0.9}}}};
}

glm::dvec4 dvr_ray(const VolumeSpline& spline, const TransferFunction& tf, const glm::dvec3& world_origin,
                   const glm::dvec3& world_dir, double step_index, const VolumeRangeGrid* bricks) {
  if (!finite3(world_origin) || !finite3(world_dir))
    throw std::invalid_argument("dvr_ray: ray origin and direction must be finite");
  if (!std::isfinite(step_index) || !(step_index > 0.0))
    throw std::invalid_argument("dvr_ray: step must be finite and > 0, got " + std::to_string(step_index));
  if (const std::string why = transfer_function_error(tf); !why.empty())
    throw std::invalid_argument("dvr_ray: transfer function: " + why);
  const std::array<int, 3>& n = spline.dims();
  if (bricks)
    for (int a = 0; a < 3; ++a)
      if (bricks->brick < 1 || bricks->dims[a] != std::max(1, (n[a] - 1 + bricks->brick - 1) / bricks->brick))
        throw std::invalid_argument("dvr_ray: the range grid was built for another volume size");
  const GridRay ray =
      clip_ray_to_grid(spline, world_origin, world_dir, std::numeric_limits<double>::infinity(), "dvr_ray");
  if (!ray.inside) return glm::dvec4(0.0);
  const glm::dvec3 entry = ray.entry, u = ray.u;
  const double length = ray.length;
  const std::int64_t segments = std::max<std::int64_t>(1, std::int64_t(std::ceil(length / step_index)));
  glm::dvec3 color(0.0);
  double alpha = 0.0;
  for (std::int64_t m = 0; m < segments && alpha < kDvrOpaque;) {
    const double s0 = double(m) * step_index;
    const double seg = std::min(step_index, length - s0);
    const glm::dvec3 p = entry + (s0 + 0.5 * seg) * u;
    if (bricks) {
      const std::array<int, 3> b = bricks->brick_of(p);
      const glm::vec2 r = bricks->at(b[0], b[1], b[2]);
      if (tf.max_opacity(r.x, r.y) == 0.0) {  // nothing visible in this brick: to its exit
        const glm::dvec3 lo = glm::dvec3(b[0], b[1], b[2]) * double(bricks->brick), hi = lo + double(bricks->brick);
        double exit_s = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
          if (u[a] > 0.0) exit_s = std::min(exit_s, (hi[a] - p[a]) / u[a]);
          if (u[a] < 0.0) exit_s = std::min(exit_s, (lo[a] - p[a]) / u[a]);
        }
        // Samples whose middle lies within the brick: up to s0 + seg/2 + exit.
        const double s_exit = s0 + 0.5 * seg + std::max(exit_s, 0.0);
        m = std::max(m + 1, std::int64_t(std::floor((s_exit - 0.5 * step_index) / step_index)) + 1);
        continue;
      }
    }
    const glm::dvec4 c = tf.at(spline.value(p));
    if (c.w > 0.0) {
      const double a = 1.0 - std::pow(1.0 - c.w, seg);
      color += (1.0 - alpha) * a * glm::dvec3(c);
      alpha += (1.0 - alpha) * a;
    }
    ++m;
  }
  if (!(alpha > 0.0)) return glm::dvec4(0.0);
  const glm::dvec3 unpremultiplied = color / alpha;
  return {srgb(unpremultiplied.x) * alpha, srgb(unpremultiplied.y) * alpha, srgb(unpremultiplied.z) * alpha, alpha};
}

DvrImage render_dvr_cpu(const VolumeSpline& spline, const TransferFunction& tf, const glm::dmat4& view,
                        const glm::dmat4& projection, int width, int height, double step_index,
                        const VolumeRangeGrid* bricks) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("render_dvr_cpu: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (const std::string why = transfer_function_error(tf); !why.empty())
    throw std::invalid_argument("render_dvr_cpu: transfer function: " + why);
  DvrImage img;
  img.width = width, img.height = height;
  img.rgba.assign(std::size_t(width) * std::size_t(height), glm::vec4(0.0f));
  const glm::ivec4 viewport(0, 0, width, height);
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, 0, width), [&](const tbb::blocked_range2d<int>& r) {
    for (int y = r.rows().begin(); y != r.rows().end(); ++y)
      for (int x = r.cols().begin(); x != r.cols().end(); ++x) {
        const PixelRay ray = pixel_ray(view, projection, viewport, x, y);
        img.rgba[std::size_t(x) + std::size_t(width) * std::size_t(y)] =
            glm::vec4(dvr_ray(spline, tf, ray.origin, ray.direction, step_index, bricks));
      }
  });
  return img;
}

}  // namespace trispline::core
