#include "core/volume/silhouette_export.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>

namespace trispline::core {
namespace {

constexpr int kHidden = -1;  // run key of hidden points; visible points use their |∇D| bin ≥ 0

bool finite_point(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

void check_input(const std::vector<SilhouettePolyline>& polylines, const glm::dmat4& vp, glm::ivec2 viewport,
                 const SvgStyle& style) {
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    const SilhouettePolyline& pl = polylines[i];
    if (pl.gradient_norm.size() != pl.points.size() || pl.visible.size() != pl.points.size())
      throw std::invalid_argument("silhouette SVG: polyline " + std::to_string(i) + " has " +
                                  std::to_string(pl.points.size()) + " points, " +
                                  std::to_string(pl.gradient_norm.size()) + " gradient norms and " +
                                  std::to_string(pl.visible.size()) + " visibility flags");
    for (std::size_t k = 0; k < pl.points.size(); ++k)
      if (!finite_point(pl.points[k]) || !std::isfinite(pl.gradient_norm[k]))
        throw std::invalid_argument("silhouette SVG: polyline " + std::to_string(i) + " point " + std::to_string(k) +
                                    " is not finite");
  }
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(vp[c][r])) throw std::invalid_argument("silhouette SVG: the view-projection is not finite");
  if (viewport.x < 1 || viewport.y < 1 || viewport.x > 65536 || viewport.y > 65536)
    throw std::invalid_argument("silhouette SVG: the viewport must be 1…65536 pixels per side");
  if (style.stroke != "hue" && style.stroke != "width" && style.stroke != "plain" && style.stroke != "glyphs" &&
      style.stroke != "fans" && style.stroke != "chromadepth")
    throw std::invalid_argument("silhouette SVG: unknown stroke style '" + style.stroke +
                                "' (hue, glyphs, fans, width, plain or chromadepth)");
  if (style.hidden != "dashed" && style.hidden != "remove")
    throw std::invalid_argument("silhouette SVG: unknown hidden mode '" + style.hidden + "' (dashed or remove)");
  if (style.bins < 1 || style.bins > 256) throw std::invalid_argument("silhouette SVG: bins must be 1…256");
  if (!(style.width_px > 0.0 && style.width_px <= 1000.0) ||
      !(style.max_width_px >= style.width_px && style.max_width_px <= 1000.0))
    throw std::invalid_argument("silhouette SVG: stroke widths must satisfy 0 < width_px ≤ max_width_px ≤ 1000");
  if (!std::isfinite(style.gradient_min) || !std::isfinite(style.gradient_max))
    throw std::invalid_argument("silhouette SVG: the gradient range is not finite");
  for (float c :
       {style.hidden_color.x, style.hidden_color.y, style.hidden_color.z, style.color.x, style.color.y, style.color.z})
    if (!(c >= 0.0f && c <= 1.0f))
      throw std::invalid_argument("silhouette SVG: hidden_color and color must be in [0, 1]");
  if (style.dash.empty() || style.dash.find_first_not_of("0123456789. ,") != std::string::npos)
    throw std::invalid_argument("silhouette SVG: dash must be numbers separated by spaces or commas");
}

// "1.25", "3", "0": two decimals, trailing zeros dropped; locale-independent (std::to_chars).
std::string number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  std::string s(buf, r.ptr);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string hex(const glm::dvec3& rgb) {
  char buf[8];
  auto byte = [](double c) { return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(rgb.x), byte(rgb.y), byte(rgb.z));
  return buf;
}

// HSV (hue in degrees, s, v in [0,1]) to RGB.
glm::dvec3 hsv(double h, double s, double v) {
  const double c = v * s, hp = h / 60.0, x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
  glm::dvec3 rgb = hp < 1   ? glm::dvec3(c, x, 0)
                   : hp < 2 ? glm::dvec3(x, c, 0)
                   : hp < 3 ? glm::dvec3(0, c, x)
                   : hp < 4 ? glm::dvec3(0, x, c)
                   : hp < 5 ? glm::dvec3(x, 0, c)
                            : glm::dvec3(c, 0, x);
  return rgb + glm::dvec3(v - c);
}

// Clips the clip-space segment a→b to the view frustum (−w ≤ x, y, z ≤ w); false when nothing is left.
bool clip_segment(const glm::dvec4& a, const glm::dvec4& b, double& t0, double& t1) {
  t0 = 0.0, t1 = 1.0;
  const std::array<glm::dvec4, 6> planes{glm::dvec4(1, 0, 0, 1),  glm::dvec4(-1, 0, 0, 1), glm::dvec4(0, 1, 0, 1),
                                         glm::dvec4(0, -1, 0, 1), glm::dvec4(0, 0, 1, 1),  glm::dvec4(0, 0, -1, 1)};
  for (const glm::dvec4& p : planes) {
    const double fa = glm::dot(p, a), fb = glm::dot(p, b);
    if (fa < 0.0 && fb < 0.0) return false;
    if (fa < 0.0) t0 = std::max(t0, fa / (fa - fb));
    if (fb < 0.0) t1 = std::min(t1, fa / (fa - fb));
    if (t0 > t1) return false;
  }
  return true;
}

// Appends the world-space polyline `pts`, projected and clipped, to the path data `d` as subpaths.
class PathWriter {
 public:
  PathWriter(const glm::dmat4& vp, glm::ivec2 viewport) : vp_(vp), size_(viewport) {}

  void append(std::string& d, const std::vector<glm::dvec3>& pts) const {
    std::string last;  // the last point written, as text; empty = pen up
    glm::dvec4 prev = vp_ * glm::dvec4(pts[0], 1.0);
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const glm::dvec4 cur = vp_ * glm::dvec4(pts[i], 1.0);
      double t0, t1;
      if (clip_segment(prev, cur, t0, t1)) {
        const std::string a = pixel(prev + t0 * (cur - prev)), b = pixel(prev + t1 * (cur - prev));
        if (!a.empty() && !b.empty()) {
          if (last.empty() || t0 > 0.0 || a != last) d += (d.empty() ? "M" : " M") + a;
          if (b != a) d += " " + b;
          last = t1 < 1.0 ? std::string() : b;
        } else {
          last.clear();
        }
      } else {
        last.clear();
      }
      prev = cur;
    }
  }

  // Pixel position of world point p (y down); false behind the eye or outside the viewport.
  bool to_pixel(const glm::dvec3& p, glm::dvec2& px) const {
    const glm::dvec4 c = vp_ * glm::dvec4(p, 1.0);
    if (!(c.w > 0.0)) return false;
    px = {(c.x / c.w * 0.5 + 0.5) * size_.x, (0.5 - c.y / c.w * 0.5) * size_.y};
    return px.x >= 0.0 && px.y >= 0.0 && px.x <= size_.x && px.y <= size_.y;
  }

 private:
  // "x y" in pixels, y down, clamped into the viewBox; empty when w ≤ 0.
  std::string pixel(const glm::dvec4& c) const {
    if (!(c.w > 0.0)) return {};
    const double x = std::clamp((c.x / c.w * 0.5 + 0.5) * size_.x, 0.0, double(size_.x));
    const double y = std::clamp((0.5 - c.y / c.w * 0.5) * size_.y, 0.0, double(size_.y));
    return number(x) + " " + number(y);
  }
  glm::dmat4 vp_;
  glm::ivec2 size_;
};

// Splits a polyline into runs of equal keys: point i owns its polyline from the midpoint with point i−1 to the
// midpoint with point i+1 (an open polyline's ends own up to themselves). emit(key, world points).
template <class Emit>
void for_each_run(const SilhouettePolyline& pl, const std::vector<int>& key, Emit&& emit) {
  const std::size_t n = pl.points.size();
  if (n < 2) return;
  const auto& p = pl.points;
  auto mid = [&](std::size_t i) { return 0.5 * (p[i % n] + p[(i + 1) % n]); };
  if (!pl.closed) {
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i;
      while (j + 1 < n && key[j + 1] == key[i]) ++j;
      std::vector<glm::dvec3> run;
      if (i > 0) run.push_back(mid(i - 1));
      run.insert(run.end(), p.begin() + i, p.begin() + j + 1);
      if (j + 1 < n) run.push_back(mid(j));
      emit(key[i], run);
      i = j + 1;
    }
    return;
  }
  std::size_t start = n;  // the first point whose key differs from its predecessor's
  for (std::size_t i = 0; i < n && start == n; ++i)
    if (key[i] != key[(i + n - 1) % n]) start = i;
  if (start == n) {
    std::vector<glm::dvec3> run(p.begin(), p.end());
    run.push_back(p[0]);
    emit(key[0], run);
    return;
  }
  for (std::size_t done = 0; done < n;) {
    const std::size_t i = (start + done) % n;
    std::size_t len = 1;
    while (done + len < n && key[(i + len) % n] == key[i]) ++len;
    std::vector<glm::dvec3> run{mid(i + n - 1)};
    for (std::size_t k = 0; k < len; ++k) run.push_back(p[(i + k) % n]);
    run.push_back(mid(i + len - 1));
    emit(key[i], run);
    done += len;
  }
}

// Fan glyphs (seed Fig. 7.11): at visible points at least 1.4 radii apart on screen, a filled sector of kFanRadiusPx
// with its apex on the curve, opening across it, kFanWidestDeg wide at ramp position 0 (lowest |∇D|) down to
// kFanNarrowestDeg at 1, appended as a closed subpath to its bin's path in `fans`. `ramp(k)` gives point k's t.
constexpr double kFanRadiusPx = 6.0, kFanWidestDeg = 150.0, kFanNarrowestDeg = 20.0;
constexpr int kFanSegments = 6;

template <class Ramp>
void append_fans(const PathWriter& writer, const SilhouettePolyline& pl, Ramp&& ramp, const std::vector<int>& key,
                 std::map<int, std::string>& fans) {
  const std::size_t n = pl.points.size();
  glm::dvec2 last(std::numeric_limits<double>::max());
  for (std::size_t k = 0; k < n; ++k) {
    if (!pl.visible[k] || key[k] < 0) continue;
    const bool wrap = pl.closed && n > 2;
    const std::size_t prev = k > 0 ? k - 1 : wrap ? n - 1 : k, next = k + 1 < n ? k + 1 : wrap ? 0 : k;
    glm::dvec2 apex, a, b;
    if (!writer.to_pixel(pl.points[k], apex) || !writer.to_pixel(pl.points[prev], a) ||
        !writer.to_pixel(pl.points[next], b))
      continue;
    const glm::dvec2 tangent = b - a;
    const double tl = glm::length(tangent);
    if (!(tl > 1e-9) || glm::length(apex - last) < 1.4 * kFanRadiusPx) continue;
    last = apex;
    const glm::dvec2 axis(-tangent.y / tl, tangent.x / tl);
    const double t = std::clamp(ramp(k), 0.0, 1.0);
    const double opening = glm::radians(kFanWidestDeg + (kFanNarrowestDeg - kFanWidestDeg) * t);
    std::string& d = fans[key[k]];
    d += (d.empty() ? "M" : " M") + number(apex.x) + " " + number(apex.y);
    for (int i = 0; i <= kFanSegments; ++i) {
      const double an = opening * (double(i) / kFanSegments - 0.5), c = std::cos(an), s = std::sin(an);
      const glm::dvec2 q = apex + kFanRadiusPx * glm::dvec2(axis.x * c - axis.y * s, axis.x * s + axis.y * c);
      d += " " + number(q.x) + " " + number(q.y);  // implicit line-tos; the fill closes the sector
    }
  }
}

void write_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("'" + path.string() + "': cannot open '" + tmp.string() + "' for writing");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error("'" + path.string() + "': writing failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("'" + path.string() + "': cannot rename the temporary file: " + ec.message());
  }
}

}  // namespace

namespace {
// One level's <g> element: its paths in `style`.
std::string svg_group(const std::vector<SilhouettePolyline>& polylines, const glm::dmat4& view_projection,
                      glm::ivec2 viewport_px, const SvgStyle& style) {
  const bool plain = style.stroke == "plain", keep_hidden = style.hidden == "dashed";

  // What the ramp follows: |∇D|, or for chromadepth the point's normalised device depth (red nearest, blue
  // farthest: ChromaDepth glasses, seed Figs. 7.8–7.9).
  const bool by_depth = style.stroke == "chromadepth";
  auto quantity = [&](const SilhouettePolyline& pl, std::size_t k) {
    if (!by_depth) return double(pl.gradient_norm[k]);
    const glm::dvec4 c = view_projection * glm::dvec4(pl.points[k], 1.0);
    return c.w > 0.0 ? c.z / c.w : 1.0;
  };
  // The ramp: the style's |∇D| range, else the visible points' own.
  double lo = by_depth ? 0.0 : style.gradient_min, hi = by_depth ? 0.0 : style.gradient_max;
  if (!(lo < hi)) {
    lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (const auto& pl : polylines)
      for (std::size_t k = 0; k < pl.points.size(); ++k)
        if (pl.visible[k]) lo = std::min(lo, quantity(pl, k)), hi = std::max(hi, quantity(pl, k));
  }
  const int bins = plain ? 1 : style.bins;
  auto bin_of = [&](double g) {
    if (!(lo < hi)) return bins / 2;
    const double t = std::clamp((g - lo) / (hi - lo), 0.0, 1.0);
    return std::min(static_cast<int>(t * bins), bins - 1);
  };

  const PathWriter writer(view_projection, viewport_px);
  std::map<int, std::string> paths;      // key → path data, hidden (−1) first
  std::map<int, std::string> fan_paths;  // fans: bin → filled sectors
  std::vector<int> key;
  for (const auto& pl : polylines) {
    key.resize(pl.points.size());
    for (std::size_t k = 0; k < pl.points.size(); ++k) key[k] = pl.visible[k] ? bin_of(quantity(pl, k)) : kHidden;
    if (style.stroke == "fans") {
      append_fans(
          writer, pl, [&](std::size_t k) { return lo < hi ? (pl.gradient_norm[k] - lo) / (hi - lo) : 0.5; }, key,
          fan_paths);
      if (keep_hidden)
        for_each_run(pl, key, [&](int k, const std::vector<glm::dvec3>& run) {
          if (k == kHidden) writer.append(paths[k], run);
        });
      continue;
    }
    if (style.stroke == "glyphs") {
      // The seed's glyphs (§7.3.4): a short stroke at each visible point along the curve (orthogonal to the projected
      // gradient), longer where |∇D| is larger: from 0.15 to 0.45 of the way to each neighbour.
      const std::size_t n = pl.points.size();
      for (std::size_t k = 0; k < n; ++k) {
        if (!pl.visible[k]) continue;
        const bool wrap = pl.closed && n > 2;
        const glm::dvec3 prev = k > 0 ? pl.points[k - 1] : wrap ? pl.points[n - 1] : pl.points[k];
        const glm::dvec3 next = k + 1 < n ? pl.points[k + 1] : wrap ? pl.points[0] : pl.points[k];
        const double f = 0.15 + 0.3 * (lo < hi ? std::clamp((pl.gradient_norm[k] - lo) / (hi - lo), 0.0, 1.0) : 0.5);
        writer.append(paths[key[k]],
                      {pl.points[k] + f * (prev - pl.points[k]), pl.points[k] + f * (next - pl.points[k])});
      }
      if (keep_hidden)
        for_each_run(pl, key, [&](int k, const std::vector<glm::dvec3>& run) {
          if (k == kHidden) writer.append(paths[k], run);
        });
      continue;
    }
    for_each_run(pl, key, [&](int k, const std::vector<glm::dvec3>& run) {
      if (k == kHidden && !keep_hidden) return;
      writer.append(paths[k], run);
    });
  }

  std::string svg = "<g fill=\"none\" stroke-linejoin=\"round\">\n";
  for (const auto& [k, d] : paths) {
    if (d.empty()) continue;
    if (k == kHidden) {
      svg += "<path class=\"hidden\" stroke=\"" + hex(glm::dvec3(style.hidden_color)) + "\" stroke-width=\"" +
             number(style.width_px) + "\" stroke-dasharray=\"" + style.dash + "\" d=\"" + d + "\"/>\n";
      continue;
    }
    const double t = (k + 0.5) / bins;  // the bin's centre on the ramp
    const glm::dvec3 base(style.color);
    glm::dvec3 colour = base;
    double width = style.width_px;
    if (style.stroke == "hue" || style.stroke == "chromadepth") {
      colour = hsv(240.0 * t, 1.0, 0.9);
    } else if (style.stroke == "width") {
      colour = base + (glm::dvec3(1.0) - base) * (0.75 * (1.0 - t));
      width = style.max_width_px + (style.width_px - style.max_width_px) * t;
    }
    std::string range;
    if (lo < hi)
      range = std::string(by_depth ? " data-depth=\"" : " data-gradient=\"") + number(lo + (hi - lo) * k / bins) + " " +
              number(lo + (hi - lo) * (k + 1) / bins) + "\"";
    svg += "<path class=\"visible\"" + range + " stroke=\"" + hex(colour) + "\" stroke-width=\"" + number(width) +
           "\" stroke-linecap=\"round\" d=\"" + d + "\"/>\n";
  }
  for (const auto& [k, d] : fan_paths)
    svg += "<path class=\"fan\" fill=\"" + hex(hsv(240.0 * (k + 0.5) / bins, 1.0, 0.9)) + "\" stroke=\"none\" d=\"" +
           d + "\"/>\n";
  svg += "</g>\n";
  return svg;
}
}  // namespace

void write_silhouettes_svg(const std::filesystem::path& path, const std::vector<SvgLayer>& layers,
                           const glm::dmat4& view_projection, glm::ivec2 viewport_px) {
  for (const SvgLayer& layer : layers) {
    if (!layer.polylines) throw std::invalid_argument("silhouette SVG: a layer without polylines");
    check_input(*layer.polylines, view_projection, viewport_px, layer.style);
  }
  const std::string w = std::to_string(viewport_px.x), h = std::to_string(viewport_px.y);
  std::string svg =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
      w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h + "\" fill=\"#ffffff\"/>\n";
  for (const SvgLayer& layer : layers) svg += svg_group(*layer.polylines, view_projection, viewport_px, layer.style);
  svg += "</svg>\n";
  write_atomically(path, svg);
}

void write_silhouettes_svg(const std::filesystem::path& path, const std::vector<SilhouettePolyline>& polylines,
                           const glm::dmat4& view_projection, glm::ivec2 viewport_px, const SvgStyle& style) {
  write_silhouettes_svg(path, {SvgLayer{&polylines, style}}, view_projection, viewport_px);
}

std::vector<std::vector<glm::vec3>> silhouette_line_strips(const std::vector<SilhouettePolyline>& polylines,
                                                           bool include_hidden) {
  std::vector<std::vector<glm::vec3>> strips;
  for (std::size_t p = 0; p < polylines.size(); ++p)
    if (polylines[p].visible.size() != polylines[p].points.size())
      throw std::invalid_argument("silhouette line strips: polyline " + std::to_string(p) + " has " +
                                  std::to_string(polylines[p].points.size()) + " points and " +
                                  std::to_string(polylines[p].visible.size()) + " visibility flags");
  for (const auto& pl : polylines) {
    const std::size_t n = pl.points.size();
    if (n < 2) continue;
    const bool all =
        include_hidden || std::all_of(pl.visible.begin(), pl.visible.end(), [](unsigned char v) { return v; });
    if (all) {
      std::vector<glm::vec3>& s = strips.emplace_back(pl.points.begin(), pl.points.end());
      if (pl.closed) s.push_back(glm::vec3(pl.points[0]));
      continue;
    }
    // Runs of visible points; a closed polyline starts after a hidden point so its wrap-around run stays whole.
    std::size_t start = 0;
    if (pl.closed)
      while (pl.visible[start]) ++start;  // terminates: some point is hidden
    std::vector<glm::vec3> run;
    const std::size_t steps = pl.closed ? n + 1 : n;
    for (std::size_t s = 0; s < steps; ++s) {
      const std::size_t i = (start + s) % n;
      if (pl.visible[i]) {
        run.push_back(glm::vec3(pl.points[i]));
      } else {
        if (run.size() >= 2) strips.push_back(run);
        run.clear();
      }
    }
    if (run.size() >= 2) strips.push_back(run);
  }
  return strips;
}

}  // namespace trispline::core
