// trispline::core stroke helpers for sketch placement: arc-length resampling, the fitted image-plane curve C(u)
// and its samples uniform in arc length with unit normals (seed §2.3.1, Eq. 2.2). All quantities in viewport pixels.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/spline/bspline_curve.h"

namespace trispline::core {

// Stroke without consecutive duplicate points (#S' ≤ #S).
std::vector<glm::dvec2> remove_duplicate_points(const std::vector<glm::dvec2>& stroke_px);

// Total polyline length, pixels.
double polyline_length(const std::vector<glm::dvec2>& pts);

// `count` (≥ 2) points evenly spaced in arc length along the polyline, first and last point kept.
std::vector<glm::dvec2> resample_by_arc_length(const std::vector<glm::dvec2>& pts, int count);

// Sum of |turning angles| (radians) of the polyline resampled to 16 segments: the stroke's complexity.
double total_turning(const std::vector<glm::dvec2>& pts);

// The least-squares image-plane curve C(u) fitted to a stroke, with how it was chosen.
struct StrokeCurve {
  BSplineCurve<glm::dvec2> curve;  // pixels; clamped knots on [0,1]
  int resampled = 0;               // points fitted
  double rms_px = 0, max_px = 0;   // fit residual at the fitted points
};

// Fits C(u) to a stroke of ≥ 2 distinct points and non-zero length (caller validates): resampled to one point per
// ~2 px (8..256 points), chord-length parameters, order = min(4, distinct points), controls = order +
// round(total_turning / 60°), capped at 16 and at the resampled count.
StrokeCurve fit_stroke_curve(const std::vector<glm::dvec2>& distinct_stroke_px);

// Samples of C at `count` (≥ 2) parameters uniform in arc length of C (measured on a dense polyline of C).
struct CurveSamples {
  std::vector<double> u;           // #count curve parameters, increasing, u[0] = 0, u[count-1] = 1
  std::vector<glm::dvec2> point;   // #count C(u_i), pixels
  std::vector<glm::dvec2> normal;  // #count unit image-plane normals N = (T.y, −T.x) (viewer's left, y down)
  double length_px = 0;            // arc length of C
};
CurveSamples sample_by_arc_length(const BSplineCurve<glm::dvec2>& c, int count);

}  // namespace trispline::core
