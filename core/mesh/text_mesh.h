// trispline::core::make_text_mesh — a line of text as a closed, extruded triangle mesh, the model the seed places on
// curved objects in §2.5 (Fig. 2.15: "strings of characters placed on top of curved objects"). The glyph outlines
// come from a TrueType/OpenType font through FreeType (quadratic and cubic outline pieces flattened into line
// segments), their faces are filled by the even–odd rule (core/mesh/planar_triangulation.h), and the side walls are
// shaded smooth along curves and sharp at corners.
#pragma once

#include <cstddef>
#include <string>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Fonts-dejavu-core's DejaVu Sans Bold (a dependency of the editor, scripts/packages.txt).
inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";
inline constexpr std::size_t kMaxTextCodepoints = 256;
inline constexpr std::size_t kMaxFontFileBytes = 64u << 20;  // refused unread above this (64 MiB)
inline constexpr int kMaxCurveSegments = 64;

struct TextMeshOptions {
  std::string font_path;      // TrueType / OpenType / Type 1 file; "" = kDefaultFontPath
  double size = 1.0;          // the font's em, world units (DejaVu's capitals stand ≈ 0.73 em)
  double depth = 0.25;        // extrusion along z, world units
  int curve_segments = 6;     // line segments per quadratic or cubic outline piece, in [1, kMaxCurveSegments]
  double letter_spacing = 0;  // extra advance between glyphs, in em
};

// `text` (UTF-8, 1..kMaxTextCodepoints code points, one line) laid along +x from the origin with the font's advances
// and kerning, baseline on y = 0, glyphs up +y, extruded from z = −depth/2 to +depth/2; then centred on its bounding
// box's middle in x and y. Front faces face +z, back faces −z, walls outward; normals per vertex (#V × 3).
// Throws std::invalid_argument for text that is empty, not UTF-8, over the limit, holds a control character, or has
// no visible glyph, for size / depth not finite and > 0, for curve_segments out of range; std::runtime_error naming
// the file for a font that cannot be read or parsed (FreeType's message), one over kMaxFontFileBytes, or one without
// a glyph for a character of the text.
TriMesh make_text_mesh(const std::string& text, const TextMeshOptions& options = {});

}  // namespace trispline::core
