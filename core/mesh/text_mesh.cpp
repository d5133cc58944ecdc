// Text as an extruded mesh: FreeType outlines, flattened, filled even–odd, walled. See text_mesh.h.
#include "core/mesh/text_mesh.h"

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/planar_triangulation.h"

namespace trispline::core {
namespace {

// Outline points of a whole text, counted before any is made (a hostile font can hold 32 K points a glyph).
constexpr std::size_t kMaxOutlinePoints = 250'000;
// A wall corner is shaded smooth when its two edges turn by less than this (curves), sharp above (corners).
const double kSmoothTurnCos = std::cos(35.0 * 3.14159265358979323846 / 180.0);

using Contour = std::vector<glm::dvec2>;

// UTF-8 to code points; throws std::invalid_argument for malformed input (overlong, surrogate, > U+10FFFF).
std::vector<char32_t> decode_utf8(const std::string& s) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < s.size();) {
    const auto b0 = static_cast<unsigned char>(s[i]);
    int n = 0;
    char32_t cp = 0;
    if (b0 < 0x80)
      n = 1, cp = b0;
    else if ((b0 & 0xE0) == 0xC0)
      n = 2, cp = b0 & 0x1F;
    else if ((b0 & 0xF0) == 0xE0)
      n = 3, cp = b0 & 0x0F;
    else if ((b0 & 0xF8) == 0xF0)
      n = 4, cp = b0 & 0x07;
    else
      throw std::invalid_argument("text is not UTF-8 (byte " + std::to_string(i) + ")");
    if (i + n > s.size()) throw std::invalid_argument("text is not UTF-8 (cut off at its end)");
    for (int k = 1; k < n; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if ((b & 0xC0) != 0x80) throw std::invalid_argument("text is not UTF-8 (byte " + std::to_string(i + k) + ")");
      cp = (cp << 6) | (b & 0x3F);
    }
    static constexpr char32_t kMinOf[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < kMinOf[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
      throw std::invalid_argument("text is not UTF-8 (byte " + std::to_string(i) + ")");
    out.push_back(cp);
    i += static_cast<std::size_t>(n);
  }
  return out;
}

std::string ft_message(FT_Error e) {
  const char* s = FT_Error_String(e);
  return s ? std::string(s) : "FreeType error " + std::to_string(e);
}

struct FtLibrary {
  FT_Library lib = nullptr;
  FT_Face face = nullptr;
  ~FtLibrary() {
    if (face) FT_Done_Face(face);
    if (lib) FT_Done_FreeType(lib);
  }
};

// FT_Outline_Decompose's callbacks: contours of flattened points, font units.
struct OutlineSink {
  std::vector<Contour> contours;
  glm::dvec2 at{0.0};
  int segments = 6;

  static glm::dvec2 pt(const FT_Vector* v) { return {double(v->x), double(v->y)}; }
  void add(const glm::dvec2& p) {
    if (contours.empty()) contours.emplace_back();
    if (contours.back().empty() || contours.back().back() != p) contours.back().push_back(p);
    at = p;
  }
  static int move_to(const FT_Vector* to, void* user) {
    auto* s = static_cast<OutlineSink*>(user);
    s->contours.emplace_back();
    s->add(pt(to));
    return 0;
  }
  static int line_to(const FT_Vector* to, void* user) {
    static_cast<OutlineSink*>(user)->add(pt(to));
    return 0;
  }
  static int conic_to(const FT_Vector* control, const FT_Vector* to, void* user) {
    auto* s = static_cast<OutlineSink*>(user);
    const glm::dvec2 p0 = s->at, c = pt(control), p1 = pt(to);
    for (int k = 1; k <= s->segments; ++k) {
      const double t = double(k) / s->segments, u = 1.0 - t;
      s->add(u * u * p0 + 2.0 * u * t * c + t * t * p1);
    }
    return 0;
  }
  static int cubic_to(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
    auto* s = static_cast<OutlineSink*>(user);
    const glm::dvec2 p0 = s->at, a = pt(c1), b = pt(c2), p1 = pt(to);
    for (int k = 1; k <= s->segments; ++k) {
      const double t = double(k) / s->segments, u = 1.0 - t;
      s->add(u * u * u * p0 + 3.0 * u * u * t * a + 3.0 * u * t * t * b + t * t * t * p1);
    }
    return 0;
  }
};

double signed_area(const Contour& c) {
  double a = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const glm::dvec2 &p = c[i], &q = c[(i + 1) % c.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

// Even–odd crossing test.
bool inside(const glm::dvec2& p, const Contour& c) {
  bool in = false;
  for (std::size_t i = 0, j = c.size() - 1; i < c.size(); j = i++) {
    const glm::dvec2 &a = c[i], &b = c[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

// Closed contours of at least three points and some area, each turned so that the filled region (even–odd) lies on
// its left: outlines counter-clockwise, holes clockwise.
std::vector<Contour> oriented_contours(std::vector<Contour> contours) {
  std::vector<Contour> kept;
  for (Contour& c : contours) {
    while (c.size() > 1 && c.front() == c.back()) c.pop_back();
    if (c.size() >= 3 && signed_area(c) != 0.0) kept.push_back(std::move(c));
  }
  for (std::size_t i = 0; i < kept.size(); ++i) {
    int depth = 0;
    for (std::size_t j = 0; j < kept.size(); ++j)
      if (j != i && inside(kept[i][0], kept[j])) ++depth;
    const bool outline = depth % 2 == 0;
    if ((signed_area(kept[i]) > 0.0) != outline) std::reverse(kept[i].begin(), kept[i].end());
  }
  return kept;
}

// One glyph's faces (front +z, back −z) and walls appended to `mesh`; points already in world units.
void append_glyph(const std::vector<Contour>& contours, double half_depth, TriMesh& mesh) {
  std::vector<glm::dvec2> points;
  std::vector<std::vector<std::uint32_t>> loops;
  for (const Contour& c : contours) {
    std::vector<std::uint32_t>& loop = loops.emplace_back();
    for (const glm::dvec2& p : c) {
      loop.push_back(static_cast<std::uint32_t>(points.size()));
      points.push_back(p);
    }
  }
  const auto tris = triangulate_nested_loops(loops, [&](std::uint32_t v) { return points[v]; });
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? half_depth : -half_depth;
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (const glm::dvec2& p : points) {
      mesh.positions.emplace_back(p.x, p.y, z);
      mesh.normals.emplace_back(0.0, 0.0, side == 0 ? 1.0 : -1.0);
    }
    for (const auto& t : tris)
      mesh.triangles.push_back(side == 0 ? glm::uvec3(base + t[0], base + t[1], base + t[2])
                                         : glm::uvec3(base + t[0], base + t[2], base + t[1]));
  }
  for (const Contour& c : contours) {
    const std::size_t n = c.size();
    std::vector<glm::dvec2> normal(n);  // of edge i → i+1: its right side, away from the filled region
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 e = c[(i + 1) % n] - c[i];
      normal[i] = glm::dvec2(e.y, -e.x) / std::hypot(e.x, e.y);
    }
    auto corner = [&](std::size_t edge, std::size_t other) {
      const double turn = glm::dot(normal[edge], normal[other]);
      const glm::dvec2 m = turn > kSmoothTurnCos ? normal[edge] + normal[other] : normal[edge];
      return glm::dvec3(m / std::hypot(m.x, m.y), 0.0);
    };
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 &a = c[i], &b = c[(i + 1) % n];
      const glm::dvec3 na = corner(i, (i + n - 1) % n), nb = corner(i, (i + 1) % n);
      const auto v = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), {glm::dvec3(a, half_depth), glm::dvec3(b, half_depth),
                                                   glm::dvec3(b, -half_depth), glm::dvec3(a, -half_depth)});
      mesh.normals.insert(mesh.normals.end(), {na, nb, nb, na});
      mesh.triangles.emplace_back(v, v + 3, v + 2);
      mesh.triangles.emplace_back(v, v + 2, v + 1);
    }
  }
}

}  // namespace

TriMesh make_text_mesh(const std::string& text, const TextMeshOptions& options) {
  if (!(std::isfinite(options.size) && options.size > 0.0))
    throw std::invalid_argument("size must be finite and above 0");
  if (!(std::isfinite(options.depth) && options.depth > 0.0))
    throw std::invalid_argument("depth must be finite and above 0");
  if (options.curve_segments < 1 || options.curve_segments > kMaxCurveSegments)
    throw std::invalid_argument("curve_segments must lie in [1, " + std::to_string(kMaxCurveSegments) + "]");
  if (!std::isfinite(options.letter_spacing) || std::abs(options.letter_spacing) > 10.0)
    throw std::invalid_argument("letter_spacing must lie in [-10, 10] em");
  const std::vector<char32_t> codepoints = decode_utf8(text);
  if (codepoints.empty()) throw std::invalid_argument("text is empty");
  if (codepoints.size() > kMaxTextCodepoints)
    throw std::invalid_argument("text has " + std::to_string(codepoints.size()) + " characters; at most " +
                                std::to_string(kMaxTextCodepoints));
  for (char32_t cp : codepoints)
    if (cp < 0x20 || (cp >= 0x7F && cp < 0xA0))
      throw std::invalid_argument("text holds a control character (one line of printable text)");

  const std::string path = options.font_path.empty() ? kDefaultFontPath : options.font_path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error("font '" + path + "': no such file");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error("font '" + path + "': " + ec.message());
  if (bytes > kMaxFontFileBytes)
    throw std::runtime_error("font '" + path + "': " + std::to_string(bytes) + " bytes; at most " +
                             std::to_string(kMaxFontFileBytes));
  FtLibrary ft;
  if (const FT_Error e = FT_Init_FreeType(&ft.lib)) throw std::runtime_error("FreeType: " + ft_message(e));
  if (const FT_Error e = FT_New_Face(ft.lib, path.c_str(), 0, &ft.face))
    throw std::runtime_error("font '" + path + "': " + ft_message(e));
  if (!FT_IS_SCALABLE(ft.face) || ft.face->units_per_EM == 0)
    throw std::runtime_error("font '" + path + "': not an outline font");
  const double scale = options.size / ft.face->units_per_EM, half_depth = 0.5 * options.depth;

  TriMesh mesh;
  double pen = 0.0;  // font units
  FT_UInt previous = 0;
  std::size_t outline_points = 0;
  const FT_Outline_Funcs funcs{
      &OutlineSink::move_to, &OutlineSink::line_to, &OutlineSink::conic_to, &OutlineSink::cubic_to, 0, 0};
  for (char32_t cp : codepoints) {
    const FT_UInt glyph = FT_Get_Char_Index(ft.face, cp);
    if (glyph == 0) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "U+%04X", static_cast<unsigned>(cp));
      throw std::runtime_error("font '" + path + "' has no glyph for " + hex);
    }
    if (previous && FT_HAS_KERNING(ft.face)) {
      FT_Vector kern{0, 0};
      if (FT_Get_Kerning(ft.face, previous, glyph, FT_KERNING_UNSCALED, &kern) == 0) pen += double(kern.x);
    }
    if (const FT_Error e = FT_Load_Glyph(ft.face, glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP))
      throw std::runtime_error("font '" + path + "': " + ft_message(e));
    const FT_GlyphSlot slot = ft.face->glyph;
    if (slot->format != FT_GLYPH_FORMAT_OUTLINE) throw std::runtime_error("font '" + path + "': not an outline font");
    outline_points +=
        static_cast<std::size_t>(slot->outline.n_points) * static_cast<std::size_t>(options.curve_segments);
    if (outline_points > kMaxOutlinePoints)
      throw std::runtime_error("font '" + path + "': the text's outlines exceed " + std::to_string(kMaxOutlinePoints) +
                               " points (lower curve_segments or shorten the text)");
    OutlineSink sink;
    sink.segments = options.curve_segments;
    if (const FT_Error e = FT_Outline_Decompose(&slot->outline, &funcs, &sink))
      throw std::runtime_error("font '" + path + "': " + ft_message(e));
    for (Contour& c : sink.contours)
      for (glm::dvec2& p : c) p = glm::dvec2(pen + p.x, p.y) * scale;
    const std::vector<Contour> contours = oriented_contours(std::move(sink.contours));
    if (!contours.empty()) append_glyph(contours, half_depth, mesh);
    pen += double(slot->metrics.horiAdvance) + options.letter_spacing * ft.face->units_per_EM;
    previous = glyph;
  }
  if (mesh.triangles.empty()) throw std::invalid_argument("text has no visible character");

  Aabb box;
  for (const glm::dvec3& p : mesh.positions) box.extend(p);
  const glm::dvec3 centre(0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y), 0.0);
  for (glm::dvec3& p : mesh.positions) p -= centre;
  for (const glm::dvec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::runtime_error("font '" + path + "': outline coordinates are not finite");
  return mesh;
}

}  // namespace trispline::core
