// trispline::gpu silhouette strokes — a volume's silhouettes (core::SilhouetteResult, seed §7.3.3) as CPU-built
// triangles in the seed's stroke styles (§7.3.4), for the renderer's silhouette pass (renderer_volume.cpp). No GL:
// tested without a context.
//
//   hue     thick lines coloured on an HSV hue ramp by |∇D|: red (low) → blue (high), seed Fig. 7.10
//   width   width and grey by |∇D|: low |∇D| thick and pale, high |∇D| thin and dark, seed Fig. 7.12
//   glyphs  per visible point a short black edge along the silhouette (orthogonal to the projected gradient G_vp,
//           seed §7.3.4: "a small edge through P_v, in the direction orthogonal to G_vp"), longer where |∇D| is larger
//           (the glyph's shape encodes the magnitude, seed Fig. 7.11), as the SVG export draws them: base × (0.6 +
//           0.8·t) with base one Newton sub-cell projected but at least 6 px; glyphs closer than 1.4 bases to the
//           previous one drawn are left out, so they stay apart; hidden runs are lines as in the other styles
//   fans    per glyph position (as glyphs) a filled fan, apex on the curve, opening across it (along the projected
//           gradient's line), 150° wide at the lowest |∇D| of the ramp down to 20° at the highest, radius the glyph
//           base, coloured on the hue ramp: seed Fig. 7.11 ("fans with smaller opening angle correspond to higher
//           gradient magnitudes ... the coloring scheme here is the same as in Figure 7.10")
//   plain   black lines
//   chromadepth  lines on the hue ramp by depth (distance from the eye): red nearest → blue farthest, for ChromaDepth
//           glasses, seed Figs. 7.8–7.9
//
// The same ramp as the SVG export (core/volume/silhouette_export.h): |∇D| mapped to t ∈ [0, 1] over the range of
// the points drawn visible; hue = 240°·t at saturation 1, value 0.9; width style grey 0.75·(1 − t), width
// max_width_px + (width_px − max_width_px)·t. Hidden points (SilhouettePolyline::visible = 0, the CPU occlusion test)
// are left out ("remove"), drawn dashed in hidden_color on top of everything ("dashed"), or drawn like the visible
// ones, on top ("show"). As in the SVG, each point owns its polyline from the midpoint with the previous point to the
// midpoint with the next.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/volume/silhouettes.h"
#include "gpu/view/overlay_geometry.h"

namespace trispline::gpu {

struct SilhouetteStrokeStyle {
  std::string stroke = "hue";     // hue | glyphs | fans | width | plain | chromadepth (VolumeSilhouetteSettings::style)
  std::string hidden = "remove";  // remove | dashed | show
  float width_px = 1.5f;          // lines of hue / plain / glyphs and hidden runs; the width style's thinnest
  float max_width_px = 4.0f;      // the width style's thickest (lowest |∇D|); ≥ width_px
  glm::vec4 plain_color{0.0f, 0.0f, 0.0f, 1.0f};       // display (sRGB) values, alpha; plain, glyphs, width's darkest
  glm::vec4 hidden_color{0.55f, 0.55f, 0.58f, 0.85f};  // dashed hidden runs
  float dash_px = 5.0f, gap_px = 4.0f;                 // dash pattern of hidden runs, pixels along the line
  double glyph_mm = 1.0;       // glyphs: world length of a glyph's edge, millimetres (6 pixels at least)
  double depth_pull_mm = 0.0;  // visible runs: depth taken this far towards the eye (same pixel), millimetres
};

// Triangles (GL_TRIANGLES) whose OverlayVertex::position is (x, y, z): x, y viewport pixels (top-left origin) and z
// the normalized device depth in [−1, 1] of the point pulled by depth_pull_mm towards the eye (0 in on_top).
struct SilhouetteStrokes {
  std::vector<OverlayVertex> depth_tested;        // visible runs ("remove", "dashed"): depth-tested against the scene
  std::vector<OverlayVertex> on_top;              // hidden runs ("dashed") and every run ("show"): no depth test
  std::size_t points = 0;                         // silhouette points drawn (in either list)
  double gradient_min = 0.0, gradient_max = 0.0;  // |∇D| range of the ramp, per millimetre (not chromadepth)
  double depth_min = 0.0, depth_max = 0.0;        // chromadepth: the ramp's distances from the eye, millimetres
};

// Builds the strokes of `polylines` (world millimetres) for a camera with `view_proj` (world → OpenGL clip space),
// `viewport` (pixels) and `eye` (millimetres). Points behind the eye (clip w ≤ 0) break a polyline. Throws
// std::invalid_argument: an unknown stroke or hidden mode, a polyline whose gradient_norm or visible size differs
// from its points, widths not 0 < width_px ≤ max_width_px, glyph_mm ≤ 0.
SilhouetteStrokes build_silhouette_strokes(const std::vector<core::SilhouettePolyline>& polylines,
                                           const glm::dmat4& view_proj, glm::ivec2 viewport, const glm::dvec3& eye,
                                           const SilhouetteStrokeStyle& style);

// The colour (sRGB, alpha 1) of a point at ramp position t ∈ [0, 1] (0 = lowest |∇D|, or nearest for chromadepth) in
// `stroke` style: the hue ramp (hue, fans, chromadepth), the width style's `plain` paled towards white by
// 0.75·(1 − t) (grey on black), else `plain` (plain, glyphs).
glm::vec4 silhouette_color(const std::string& stroke, double t, const glm::vec4& plain = {0.0f, 0.0f, 0.0f, 1.0f});

}  // namespace trispline::gpu
