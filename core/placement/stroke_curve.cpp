// Stroke resampling, curve fit and arc-length sampling for sketch placement. See stroke_curve.h.
#include "core/placement/stroke_curve.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/spline/fitting.h"

namespace trispline::core {

std::vector<glm::dvec2> remove_duplicate_points(const std::vector<glm::dvec2>& stroke_px) {
  std::vector<glm::dvec2> out;
  for (const auto& p : stroke_px)
    if (out.empty() || p != out.back()) out.push_back(p);
  return out;
}

double polyline_length(const std::vector<glm::dvec2>& pts) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += glm::length(pts[i] - pts[i - 1]);
  return len;
}

std::vector<glm::dvec2> resample_by_arc_length(const std::vector<glm::dvec2>& pts, int count) {
  std::vector<double> cum(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) cum[i] = cum[i - 1] + glm::length(pts[i] - pts[i - 1]);
  const double total = cum.back();
  std::vector<glm::dvec2> out(static_cast<std::size_t>(count));
  std::size_t seg = 1;
  for (int k = 0; k < count; ++k) {
    const double s = total * k / (count - 1);
    while (seg + 1 < pts.size() && cum[seg] < s) ++seg;
    const double len = cum[seg] - cum[seg - 1];
    const double f = len > 0.0 ? std::clamp((s - cum[seg - 1]) / len, 0.0, 1.0) : 0.0;
    out[k] = pts[seg - 1] + f * (pts[seg] - pts[seg - 1]);
  }
  out.front() = pts.front();
  out.back() = pts.back();
  return out;
}

double total_turning(const std::vector<glm::dvec2>& pts) {
  const std::vector<glm::dvec2> q = resample_by_arc_length(pts, 17);
  double turn = 0.0;
  for (std::size_t i = 2; i < q.size(); ++i) {
    const glm::dvec2 a = q[i - 1] - q[i - 2], b = q[i] - q[i - 1];
    if (glm::length(a) == 0.0 || glm::length(b) == 0.0) continue;
    turn += std::abs(std::atan2(a.x * b.y - a.y * b.x, glm::dot(a, b)));
  }
  return turn;
}

StrokeCurve fit_stroke_curve(const std::vector<glm::dvec2>& distinct) {
  const double len = polyline_length(distinct);
  const int m = std::clamp(static_cast<int>(std::ceil(len / 2.0)) + 1, 8, 256);
  const std::vector<glm::dvec2> pts = resample_by_arc_length(distinct, m);
  const int order = std::min(4, static_cast<int>(distinct.size()));
  const double sixty_deg = std::numbers::pi / 3.0;
  int controls = order + static_cast<int>(std::lround(total_turning(distinct) / sixty_deg));
  controls = std::clamp(controls, order, std::max(order, std::min(16, m)));
  const std::vector<double> t = parametrize(pts, Parametrization::ChordLength);
  StrokeCurve sc{fit_curve(pts, t, order, controls), m, 0.0, 0.0};
  double sum2 = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double e = glm::length(sc.curve.eval(t[i]) - pts[i]);
    sum2 += e * e;
    sc.max_px = std::max(sc.max_px, e);
  }
  sc.rms_px = std::sqrt(sum2 / static_cast<double>(pts.size()));
  return sc;
}

CurveSamples sample_by_arc_length(const BSplineCurve<glm::dvec2>& c, int count) {
  const int dense = std::max(1024, 8 * count);
  std::vector<double> cum(static_cast<std::size_t>(dense), 0.0);
  glm::dvec2 prev = c.eval(0.0);
  for (int k = 1; k < dense; ++k) {
    const glm::dvec2 p = c.eval(static_cast<double>(k) / (dense - 1));
    cum[k] = cum[k - 1] + glm::length(p - prev);
    prev = p;
  }
  CurveSamples s;
  s.length_px = cum.back();
  s.u.resize(static_cast<std::size_t>(count));
  int seg = 1;
  for (int i = 0; i < count; ++i) {
    const double target = s.length_px * i / (count - 1);
    while (seg + 1 < dense && cum[seg] < target) ++seg;
    const double len = cum[seg] - cum[seg - 1];
    const double f = len > 0.0 ? std::clamp((target - cum[seg - 1]) / len, 0.0, 1.0) : 0.0;
    s.u[i] = (seg - 1 + f) / (dense - 1);
  }
  s.u.front() = 0.0;
  s.u.back() = 1.0;
  for (int i = 0; i < count; ++i) {
    const std::vector<glm::dvec2> d = c.derivatives(s.u[i], 1);
    glm::dvec2 tan = d[1];
    if (!(glm::length(tan) > 1e-12)) {  // stationary point of the parametrisation: use the chord of neighbours
      const double a = std::max(0.0, s.u[i] - 1e-3), b = std::min(1.0, s.u[i] + 1e-3);
      tan = c.eval(b) - c.eval(a);
    }
    tan = glm::length(tan) > 0.0 ? glm::normalize(tan) : glm::dvec2(1.0, 0.0);
    s.point.push_back(d[0]);
    s.normal.emplace_back(tan.y, -tan.x);
  }
  return s;
}

}  // namespace trispline::core
