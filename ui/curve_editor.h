// trispline::ui curve editor — a small ImGui widget editing a piecewise-linear profile f(u) over u ∈ [0,1] with a
// factor axis 0..3 (the Sketch tool's width profile d(u) and height profile h(u), seed §2.4.1, Eq. 2.5): drag a
// point, double-click to add one, right-click to remove one, Reset for the constant 1. The end points stay at u = 0
// and u = 1.
//
// Points snap to u = i/32 so that the profile is exactly the piecewise-linear function through uniform samples
// (profile_samples), which is what place.sketch's "width_profile"/"height_profile" take.
#pragma once

#include <string>
#include <vector>

namespace trispline::ui {

struct CurvePoint {
  double u = 0.0;  // in [0,1], a multiple of 1/kCurveGrid
  double f = 1.0;  // factor in [kCurveMinFactor, kCurveMaxFactor]
};

constexpr int kCurveGrid = 32;            // u snaps to multiples of 1/32
constexpr double kCurveMinFactor = 0.05;  // place.sketch needs factors > 0
constexpr double kCurveMaxFactor = 3.0;

// The constant profile: (0, 1), (1, 1).
std::vector<CurvePoint> flat_curve();
bool is_flat(const std::vector<CurvePoint>& points);  // every factor is 1

// Value of the piecewise-linear curve at u (points sorted by u, ≥ 2, first at 0, last at 1).
double curve_value(const std::vector<CurvePoint>& points, double u);

// The curve as K + 1 uniform samples f(i/K), K the smallest power of two ≤ kCurveGrid that puts every point on a
// sample (exact: the piecewise-linear function through them is the curve). Empty when the curve is flat (the
// command field is then omitted).
std::vector<double> profile_samples(const std::vector<CurvePoint>& points);

// The curve through uniform samples (≥ 2) — the inverse of profile_samples (u rounded to the grid); fewer than 2
// samples give the flat curve.
std::vector<CurvePoint> curve_from_samples(const std::vector<double>& samples);

// Sanitises `points` in place: sorted, u on the grid and in [0,1], one point per u, ends at 0 and 1, factors clamped.
void normalise_curve(std::vector<CurvePoint>& points);

// Draws the widget (a framed plot `height` pixels tall, the full available width, and a Reset button) with `tip` as
// the tooltip. Returns true when an edit finished (a drag released, a point added or removed, Reset), i.e. once per
// user action, so the caller issues one command per action.
bool curve_editor(const char* id, std::vector<CurvePoint>& points, const char* tip, float height = 90.0f);

}  // namespace trispline::ui
