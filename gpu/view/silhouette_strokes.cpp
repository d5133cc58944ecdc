// Silhouette strokes in the seed's styles. See silhouette_strokes.h.
#include "gpu/view/silhouette_strokes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace trispline::gpu {
namespace {

enum List { kDropped = -1, kTested = 0, kOnTop = 1 };

constexpr float kGlyphMinPx = 6.0f;  // a glyph's edge at least this long, pixels
constexpr int kFanSegments = 6;      // triangles of one fan glyph
// A fan glyph's opening angle at the lowest and the highest |∇D| of the ramp, degrees (seed Fig. 7.11: "fans with
// smaller opening angle correspond to higher gradient magnitudes").
constexpr float kFanWidestDeg = 150.0f, kFanNarrowestDeg = 20.0f;

// One silhouette point on screen.
struct Sample {
  glm::vec2 px{0.0f};
  float z = 0.0f;
  glm::vec4 color{0.0f};
  float width = 1.0f;
  int list = kDropped;
  bool dashed = false;
  float t = 0.5f;  // ramp position
};

// HSV (hue in degrees, s, v in [0,1]) to RGB, as the SVG export.
glm::vec3 hsv(double h, double s, double v) {
  const double c = v * s, hp = h / 60.0, x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
  const glm::dvec3 rgb = hp < 1   ? glm::dvec3(c, x, 0)
                         : hp < 2 ? glm::dvec3(x, c, 0)
                         : hp < 3 ? glm::dvec3(0, c, x)
                         : hp < 4 ? glm::dvec3(0, x, c)
                         : hp < 5 ? glm::dvec3(x, 0, c)
                                  : glm::dvec3(c, 0, x);
  return glm::vec3(rgb + glm::dvec3(v - c));
}

class Builder {
 public:
  Builder(const glm::dmat4& vp, glm::ivec2 viewport, const glm::dvec3& eye, const SilhouetteStrokeStyle& style)
      : vp_(vp), size_(viewport), eye_(eye), style_(style) {}

  // Pixel position of world point p; false behind the eye or not finite.
  bool pixel(const glm::dvec3& p, glm::vec2& px) const {
    const glm::dvec4 c = vp_ * glm::dvec4(p, 1.0);
    if (!(c.w > 1e-12)) return false;
    const double x = (c.x / c.w * 0.5 + 0.5) * size_.x, y = (0.5 - c.y / c.w * 0.5) * size_.y;
    if (!std::isfinite(x) || !std::isfinite(y)) return false;
    px = glm::vec2(float(x), float(y));
    return true;
  }

  // NDC depth of p moved depth_pull_mm towards the eye (at most 90 % of the way), clamped to [−1, 1].
  float depth(const glm::dvec3& p) const {
    const glm::dvec3 to_eye = eye_ - p;
    const double dist = glm::length(to_eye);
    const double f = dist > 0.0 ? std::min(style_.depth_pull_mm / dist, 0.9) : 0.0;
    const glm::dvec4 c = vp_ * glm::dvec4(p + f * to_eye, 1.0);
    const double z = c.w > 1e-12 ? c.z / c.w : -1.0;
    return float(std::clamp(std::isfinite(z) ? z : -1.0, -1.0, 1.0));
  }

  // A quad from a to b with each end's width and colour.
  static void segment(std::vector<OverlayVertex>& out, const Sample& a, const Sample& b) {
    const glm::vec2 d = b.px - a.px;
    const float len = glm::length(d);
    if (!(len > 1e-6f)) return;
    const glm::vec2 n = glm::vec2(-d.y, d.x) / len;
    const glm::vec2 na = n * (0.5f * a.width), nb = n * (0.5f * b.width);
    const OverlayVertex a0{{a.px + na, a.z}, a.color}, a1{{a.px - na, a.z}, a.color};
    const OverlayVertex b0{{b.px + nb, b.z}, b.color}, b1{{b.px - nb, b.z}, b.color};
    out.insert(out.end(), {a0, a1, b0, b0, a1, b1});
  }

  // A filled fan (circular sector) with its apex at s, its axis along the unit `axis`, `opening` radians wide and
  // `radius` pixels long, in s's colour: kFanSegments triangles.
  static void fan(std::vector<OverlayVertex>& out, const Sample& s, glm::vec2 axis, float opening, float radius) {
    const OverlayVertex apex{{s.px, s.z}, s.color};
    auto rim = [&](int i) {
      const float a = opening * (float(i) / kFanSegments - 0.5f), c = std::cos(a), si = std::sin(a);
      const glm::vec2 d(axis.x * c - axis.y * si, axis.x * si + axis.y * c);
      return OverlayVertex{{s.px + radius * d, s.z}, s.color};
    };
    for (int i = 0; i < kFanSegments; ++i) out.insert(out.end(), {apex, rim(i), rim(i + 1)});
  }

  // A disc (round join) of the sample's width.
  static void disc(std::vector<OverlayVertex>& out, const Sample& s, int segments = 8) {
    const float r = 0.5f * s.width;
    for (int k = 0; k < segments; ++k) {
      const float a0 = 6.2831853f * float(k) / float(segments), a1 = 6.2831853f * float(k + 1) / float(segments);
      out.insert(out.end(), {OverlayVertex{{s.px, s.z}, s.color},
                             OverlayVertex{{s.px + r * glm::vec2(std::cos(a0), std::sin(a0)), s.z}, s.color},
                             OverlayVertex{{s.px + r * glm::vec2(std::cos(a1), std::sin(a1)), s.z}, s.color}});
    }
  }

  // Segment a → b into its list, dashed along the polyline's running arc length when the samples are.
  void emit(SilhouetteStrokes& out, const Sample& a, const Sample& b, double& dash_pos) const {
    if (a.list == kDropped) return;
    std::vector<OverlayVertex>& list = a.list == kTested ? out.depth_tested : out.on_top;
    if (!a.dashed) return segment(list, a, b);
    const double len = glm::length(glm::dvec2(b.px - a.px));
    const double dash = std::max<double>(style_.dash_px, 0.5), period = dash + std::max<double>(style_.gap_px, 0.0);
    double t = 0.0;
    while (t < len) {
      const double phase = std::fmod(dash_pos + t, period);
      if (phase < dash) {
        const double end = std::min(len, t + dash - phase);
        Sample s = a, e = b;
        s.px = a.px + float(t / len) * (b.px - a.px);
        e.px = a.px + float(end / len) * (b.px - a.px);
        e.color = a.color, e.width = a.width, e.z = a.z;
        segment(list, s, e);
        t = end;
      } else {
        t += period - phase;
      }
    }
    dash_pos += len;
  }

 private:
  const glm::dmat4& vp_;
  glm::ivec2 size_;
  glm::dvec3 eye_;
  const SilhouetteStrokeStyle& style_;
};

void check(const std::vector<core::SilhouettePolyline>& polylines, const SilhouetteStrokeStyle& s) {
  if (s.stroke != "hue" && s.stroke != "glyphs" && s.stroke != "fans" && s.stroke != "width" && s.stroke != "plain" &&
      s.stroke != "chromadepth")
    throw std::invalid_argument("silhouette strokes: unknown style '" + s.stroke +
                                "' (hue, glyphs, fans, width, plain or chromadepth)");
  if (s.hidden != "remove" && s.hidden != "dashed" && s.hidden != "show")
    throw std::invalid_argument("silhouette strokes: unknown hidden mode '" + s.hidden + "' (remove, dashed or show)");
  if (!(s.width_px > 0.0f) || !(s.max_width_px >= s.width_px))
    throw std::invalid_argument("silhouette strokes: widths must satisfy 0 < width_px ≤ max_width_px");
  if (!(s.glyph_mm > 0.0) || !std::isfinite(s.glyph_mm))
    throw std::invalid_argument("silhouette strokes: glyph_mm must be finite and > 0");
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    const core::SilhouettePolyline& pl = polylines[i];
    if (pl.gradient_norm.size() != pl.points.size() || pl.visible.size() != pl.points.size())
      throw std::invalid_argument("silhouette strokes: polyline " + std::to_string(i) + " has " +
                                  std::to_string(pl.points.size()) + " points, " +
                                  std::to_string(pl.gradient_norm.size()) + " gradient norms and " +
                                  std::to_string(pl.visible.size()) + " visibility flags");
  }
}

}  // namespace

glm::vec4 silhouette_color(const std::string& stroke, double t, const glm::vec4& plain) {
  t = std::clamp(std::isfinite(t) ? t : 0.5, 0.0, 1.0);
  if (stroke == "hue" || stroke == "fans" || stroke == "chromadepth") return glm::vec4(hsv(240.0 * t, 1.0, 0.9), 1.0f);
  if (stroke == "width") {  // from `plain` (high |∇D|) towards white (low): grey 0.75·(1 − t) over black
    const glm::dvec3 base(plain);
    return glm::vec4(glm::vec3(base + (glm::dvec3(1.0) - base) * (0.75 * (1.0 - t))), 1.0f);
  }
  return plain;
}

SilhouetteStrokes build_silhouette_strokes(const std::vector<core::SilhouettePolyline>& polylines,
                                           const glm::dmat4& view_proj, glm::ivec2 viewport, const glm::dvec3& eye,
                                           const SilhouetteStrokeStyle& style) {
  check(polylines, style);
  SilhouetteStrokes out;
  const bool show = style.hidden == "show";
  // What the ramp follows: |∇D|, or for chromadepth the point's depth (its distance from the eye: ChromaDepth
  // glasses show red nearest and blue farthest, seed Figs. 7.8–7.9).
  const bool by_depth = style.stroke == "chromadepth";
  auto quantity = [&](const core::SilhouettePolyline& pl, std::size_t k) {
    return by_depth ? glm::length(pl.points[k] - eye) : double(pl.gradient_norm[k]);
  };
  // The ramp over the points drawn as visible (all of them when none is).
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (int pass = 0; pass < 2 && !(lo <= hi); ++pass)
    for (const core::SilhouettePolyline& pl : polylines)
      for (std::size_t k = 0; k < pl.points.size(); ++k)
        if ((pass == 1 || show || pl.visible[k]) && std::isfinite(quantity(pl, k)))
          lo = std::min(lo, quantity(pl, k)), hi = std::max(hi, quantity(pl, k));
  if (!(lo <= hi)) lo = hi = 0.0;
  if (by_depth)
    out.depth_min = lo, out.depth_max = hi;
  else
    out.gradient_min = lo, out.gradient_max = hi;
  auto ramp = [&](double q) { return lo < hi ? float(std::clamp((q - lo) / (hi - lo), 0.0, 1.0)) : 0.5f; };

  const Builder b(view_proj, viewport, eye, style);
  const bool fans = style.stroke == "fans", glyphs = style.stroke == "glyphs" || fans;
  std::vector<Sample> samples;
  std::vector<char> valid;
  for (const core::SilhouettePolyline& pl : polylines) {
    const std::size_t n = pl.points.size();
    if (n == 0) continue;
    samples.assign(n, Sample{});
    valid.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      Sample& s = samples[k];
      const bool visible = pl.visible[k] != 0;
      if (!b.pixel(pl.points[k], s.px)) continue;  // behind the eye: breaks the polyline
      valid[k] = 1;
      if (!visible && style.hidden == "remove") continue;  // kDropped: owns its half-segments, draws nothing
      s.t = ramp(quantity(pl, k));
      s.list = visible && !show ? kTested : kOnTop;
      s.z = s.list == kTested ? b.depth(pl.points[k]) : 0.0f;
      if (!visible && !show) {
        s.dashed = true;
        s.color = style.hidden_color;
        s.width = style.width_px;
      } else {
        s.color = silhouette_color(style.stroke, s.t, style.plain_color);
        s.width =
            style.stroke == "width" ? style.max_width_px + (style.width_px - style.max_width_px) * s.t : style.width_px;
      }
      ++out.points;
    }

    if (glyphs) {
      // One glyph per point drawn as a glyph (not dashed): an edge along the curve, base × (0.6 + 0.8·t) long, base =
      // the glyph_mm edge projected but at least kGlyphMinPx; centres closer than 1.4 bases to the previous glyph are
      // skipped, so the glyphs stay apart. Dashed hidden runs are drawn as lines below.
      glm::vec2 last(std::numeric_limits<float>::max());
      for (std::size_t k = 0; k < n; ++k) {
        Sample& s = samples[k];
        if (!valid[k] || s.list == kDropped || s.dashed) continue;
        const Sample glyph = s;
        s.list = kDropped;  // not part of a line
        const std::size_t prev = k > 0 ? k - 1 : pl.closed ? n - 1 : k;
        const std::size_t next = k + 1 < n ? k + 1 : pl.closed ? 0 : k;
        const glm::dvec3 tangent = pl.points[next] - pl.points[prev];
        const double tl = glm::length(tangent);
        if (!(tl > 0.0)) continue;
        const glm::dvec3 half = tangent / tl * (0.5 * style.glyph_mm);
        glm::vec2 a, e;
        if (!b.pixel(pl.points[k] - half, a) || !b.pixel(pl.points[k] + half, e)) continue;
        glm::vec2 dir = e - a;
        const float projected = glm::length(dir);
        if (!(projected > 1e-6f)) continue;
        dir /= projected;
        const float base = std::max(projected, kGlyphMinPx);
        if (glm::length(glyph.px - last) < 1.4f * base) continue;
        last = glyph.px;
        std::vector<OverlayVertex>& list = glyph.list == kTested ? out.depth_tested : out.on_top;
        if (fans) {
          // Fig. 7.11: a fan across the curve (along the projected gradient's line), wide where |∇D| is low and
          // narrow where it is high, in the hue ramp's colour.
          const float opening = glm::radians(kFanWidestDeg + (kFanNarrowestDeg - kFanWidestDeg) * glyph.t);
          Builder::fan(list, glyph, glm::vec2(-dir.y, dir.x), opening, base);
          continue;
        }
        const float len = base * (0.6f + 0.8f * glyph.t);
        Sample p0 = glyph, p1 = glyph;
        p0.px = glyph.px - 0.5f * len * dir, p1.px = glyph.px + 0.5f * len * dir;
        Builder::segment(list, p0, p1);
      }
    }

    // Lines: samples closer than 0.75 px to the last one kept (same list) are merged into it; a point behind the eye
    // breaks the polyline. Between samples of different lists the midpoint divides the segment.
    double dash_pos = 0.0;
    std::size_t first = n, last = n;
    bool broken = false;
    auto join = [&](const Sample& s) {
      if (s.list != kDropped && s.width >= 2.5f && !s.dashed)
        Builder::disc(s.list == kTested ? out.depth_tested : out.on_top, s);
    };
    auto connect = [&](const Sample& a, const Sample& c) {
      if (a.list == c.list && a.dashed == c.dashed) return b.emit(out, a, c, dash_pos);
      Sample ma = a, mc = c;
      ma.px = mc.px = 0.5f * (a.px + c.px);
      b.emit(out, a, ma, dash_pos);
      b.emit(out, mc, c, dash_pos);
    };
    for (std::size_t k = 0; k < n; ++k) {
      if (!valid[k]) {
        broken = true;
        continue;
      }
      const Sample& s = samples[k];
      if (last != n && !broken) {
        const Sample& l = samples[last];
        if (k + 1 < n && l.list == s.list && l.dashed == s.dashed && glm::length(s.px - l.px) < 0.75f) continue;
        connect(l, s);
        join(s);
      } else {
        join(s);
      }
      if (first == n) first = k;
      last = k;
      broken = false;
    }
    if (pl.closed && first != n && last != first && valid[0] && valid[n - 1]) connect(samples[last], samples[first]);
  }
  return out;
}

}  // namespace trispline::gpu
