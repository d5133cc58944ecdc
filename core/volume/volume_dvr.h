// trispline::core direct volume rendering of a scalar trivariate B-spline (seed §7.4, Fig. 7.7): emission–absorption
// along each pixel's ray through a 1-D transfer function, on the spline itself. The CPU double reference of the GLSL
// ray marcher (gpu/eval/volume_gl.h VolumeIsoRenderer::draw_dvr, shaders/volume_dvr.frag.glsl), which takes the same
// samples in float.
//
// The transfer function maps a value of D (the volume's units: HU for CT) to a linear RGB colour and an opacity per
// index unit of path, piecewise linearly between its points and constant beyond the first and the last. The march
// (the same on the GPU): the pixel's ray (pixel_ray, iso_raycast.h) is mapped to index space and clipped to the grid
// box [0, n−1]³; the clipped length L is cut into N = ⌈L / step⌉ segments of `step` index units (the last one
// shorter, ℓ_m = min(step, L − m·step)), each sampled at its middle; a sample of colour c and opacity a per index
// unit absorbs α = 1 − (1 − a)^ℓ (opacity correction for the segment length, Engel et al. 2006, "Real-Time Volume
// Graphics" §1.4.3) and adds (1 − A)·α·c to the colour, front to back (A: the opacity so far). The march ends after
// the last segment or once A ≥ kDvrOpaque. Segments inside bricks whose value range maps to zero opacity (convex hull
// property: D lies between its controls' min and max) are skipped whole, which changes nothing.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/volume/iso_raycast.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

// The march stops once the accumulated opacity reaches this (the rest of the ray adds < 0.4 % of its colour).
inline constexpr double kDvrOpaque = 0.996;
// At most this many points in a transfer function (the GLSL uniform arrays' size).
inline constexpr int kMaxTransferPoints = 16;

// One point of a transfer function: at D = value, colour rgb (linear, [0, 1]) and opacity a per index unit ([0, 1]).
struct TransferPoint {
  double value = 0.0;
  glm::dvec4 rgba{0.0};
};

// A 1-D transfer function: points sorted by strictly increasing value.
struct TransferFunction {
  std::vector<TransferPoint> points;

  // Colour and opacity at D = v: linear between the two points around v, the end points' beyond them.
  glm::dvec4 at(double v) const;
  // The largest opacity over values [lo, hi] (the points inside and both ends): 0 means the interval is invisible.
  double max_opacity(double lo, double hi) const;
  bool operator==(const TransferFunction& o) const;
};

// "" when `tf` is usable, else why not (for CommandError): 2 to kMaxTransferPoints points, finite values strictly
// increasing, every colour and opacity component in [0, 1].
std::string transfer_function_error(const TransferFunction& tf);

// A CT preset in Hounsfield units: air transparent, skin and soft tissue a faint orange, bone opaque ivory.
TransferFunction ct_transfer_function();

// Premultiplied RGBA of one ray, sRGB-encoded colour (as the GLSL writes it before blending): rgb = srgb(C / A) · A,
// a = A, where C and A are the composited linear colour and opacity; zero when the ray misses the grid box.
// world_origin, world_dir: millimetres (world_dir need not be unit); step_index: segment length, index units.
// bricks: optional empty-space skipping (same result). Throws std::invalid_argument: non-finite or zero ray, step not
// finite or ≤ 0, a transfer function transfer_function_error refuses, bricks of another grid size.
glm::dvec4 dvr_ray(const VolumeSpline& spline, const TransferFunction& tf, const glm::dvec3& world_origin,
                   const glm::dvec3& world_dir, double step_index = 0.5, const VolumeRangeGrid* bricks = nullptr);

// dvr_ray for every pixel of a width × height viewport at (0, 0): rgba[x + width·y], bottom row first (the order
// glReadPixels returns), premultiplied, sRGB-encoded colour. Throws as dvr_ray, and std::invalid_argument for a
// non-positive size. Multi-threaded (oneTBB); the same image for any thread count.
struct DvrImage {
  int width = 0, height = 0;
  std::vector<glm::vec4> rgba;
};
DvrImage render_dvr_cpu(const VolumeSpline& spline, const TransferFunction& tf, const glm::dmat4& view,
                        const glm::dmat4& projection, int width, int height, double step_index = 0.5,
                        const VolumeRangeGrid* bricks = nullptr);

}  // namespace trispline::core
