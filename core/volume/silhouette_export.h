// trispline::core silhouette exports: an SVG line drawing for illustrators and line strips for glTF.
//
//   write_silhouettes_svg    polylines projected to pixels, visible runs solid, hidden runs dashed grey or left out,
//                            stroked by |∇D| in the seed's styles (§7.3.4, Fig. 7.10 hue, Fig. 7.12 width and grey)
//   silhouette_line_strips   polylines as float world-space strips for GltfNode::line_strips (core/mesh/gltf_io.h)
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/volume/silhouettes.h"

namespace trispline::core {

// How write_silhouettes_svg strokes the silhouettes. |∇D| (SilhouettePolyline::gradient_norm) is mapped to
// t ∈ [0, 1] over [gradient_min, gradient_max] and quantised into `bins` levels, each one <path> element.
struct SvgStyle {
  // "hue": colour on an HSV hue ramp, red (hue 0°, low |∇D|) to blue (240°, high |∇D|), seed Fig. 7.10;
  // "width": high |∇D| thin and dark, low |∇D| thick and pale grey, seed Fig. 7.12; "plain": black; "glyphs": a
  // short black stroke along the curve at each visible point, longer where |∇D| is larger (seed Fig. 7.11); "fans":
  // at visible points 8.4 px apart a filled fan (6 px, <path class="fan">) across the curve, 150° wide at low |∇D|
  // down to 20° at high |∇D|, in the hue ramp's colour (seed Fig. 7.11);
  // "chromadepth": the hue ramp by depth instead of |∇D| (normalised device depth over the visible points), red
  // nearest to blue farthest, for ChromaDepth glasses (seed Figs. 7.8–7.9); the bins' paths carry data-depth.
  std::string stroke = "hue";
  // "dashed": hidden runs drawn dashed in hidden_color under the visible ones; "remove": hidden runs left out.
  std::string hidden = "dashed";
  double width_px = 1.5;      // stroke width of "hue" and "plain" and of hidden runs; "width": the thinnest stroke
  double max_width_px = 4.0;  // "width": the thickest stroke (lowest |∇D|); ≥ width_px
  // |∇D| range of the ramp, per millimetre; gradient_min ≥ gradient_max: the range of the visible points drawn.
  double gradient_min = 0.0, gradient_max = 0.0;
  int bins = 16;                 // quantisation levels of |∇D| (1…256)
  glm::vec3 hidden_color{0.6f};  // sRGB in [0, 1] (SVG colours are sRGB)
  glm::vec3 color{0.0f};         // sRGB in [0, 1]: "plain" and "glyphs" strokes; "width": the darkest, paled to white
  std::string dash = "4 3";      // SVG stroke-dasharray of hidden runs, pixels
};

// Writes `polylines` (world millimetres) as an SVG of viewport_px pixels: viewBox "0 0 W H", a white background
// rect, y down. A point p goes to clip space by view_projection · (p, 1) (OpenGL conventions, as gpu/ and Camera
// produce), then to pixels x = (ndc.x + 1)/2·W, y = (1 − ndc.y)/2·H; segments are clipped to the view frustum, so
// every coordinate lies in the viewBox. Each point owns the stretch of its polyline from the midpoint with the
// previous point to the midpoint with the next; consecutive points of the same visibility and |∇D| bin form one run,
// and all runs of one bin are subpaths of one <path>, so the file stays small.
// Throws std::invalid_argument: a polyline whose gradient_norm or visible size differs from its points, a non-finite
// point, matrix or style number, a viewport side outside 1…65536, an unknown stroke or hidden mode, bins outside
// 1…256. Throws std::runtime_error when the file cannot be written (it is written to "<path>.tmp" and renamed, so a
// failure leaves no half file).
void write_silhouettes_svg(const std::filesystem::path& path, const std::vector<SilhouettePolyline>& polylines,
                           const glm::dmat4& view_projection, glm::ivec2 viewport_px, const SvgStyle& style = {});

// Several iso-levels' silhouettes in one SVG (seed Figs. 7.4–7.6, 7.12): one <g> per layer, in order (later layers
// drawn over earlier ones), each as above in its own style. Throws as above, and for a layer without polylines.
struct SvgLayer {
  const std::vector<SilhouettePolyline>* polylines = nullptr;
  SvgStyle style;
};
void write_silhouettes_svg(const std::filesystem::path& path, const std::vector<SvgLayer>& layers,
                           const glm::dmat4& view_projection, glm::ivec2 viewport_px);

// The polylines as line strips (world units, float): with include_hidden every polyline with ≥ 2 points is one strip
// (a closed one repeats its first point at the end); without, each run of visible points with ≥ 2 points is one.
// Throws std::invalid_argument when a polyline's visible size differs from its points.
std::vector<std::vector<glm::vec3>> silhouette_line_strips(const std::vector<SilhouettePolyline>& polylines,
                                                           bool include_hidden);

}  // namespace trispline::core
