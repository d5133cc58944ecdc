// A ring-shaped control lattice, periodic along u, for objects travelling around a ring without a seam (seed §4.5,
// Fig. 4.5), optionally with its cross-section twisted round the ring's centre line: a half twist makes a Möbius band
// (Fig. 4.6).
#pragma once

#include <glm/glm.hpp>

#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// Turns of the ring that one period of u covers for a cross-section twisted by `twist_deg` degrees per turn: the
// smallest laps ≥ 1 with laps·twist_deg a multiple of 360 (0 → 1, ±90 → 4, ±180 → 2, ±270 → 4, ±360 → 1, ...).
// Throws std::invalid_argument unless twist_deg is a multiple of 90 in [−720, 720].
int ring_twist_laps(double twist_deg);

// Control points of a periodic-in-u lattice around `center` (world units), u from +x towards +z, v outwards across
// the ring (width `width`), w up (height `height`); controls and orders per axis (order = degree + 1, 2..4).
// The circle of control points is enlarged so that the B-spline's centre line (v = ½, w = 0) passes through radius
// `radius` at the control points' parameters (a uniform B-spline over a control polygon on a circle lies inside it).
// twist_deg (degrees per turn, a multiple of 90 in [−720, 720]): the cross-section turns about the centre line by
// twist_deg per turn of the ring, positive from outwards (v) towards up (w); one period of u then covers
// ring_twist_laps(twist_deg) turns (180: a Möbius band whose bottom face w = 0 is one surface met from both sides,
// the second turn upside down). twist_deg = 0 gives the untwisted ring, bit for bit as before the twist existed.
// Throws std::invalid_argument on bad sizes (non-positive or non-finite sizes, radius ≤ width / 2, orders outside 2..4,
// fewer control points than the order) and, when twisted, on radius ≤ hypot(width / 2, height) (the turning
// cross-section would cross the ring's axis), controls.x not a multiple of the laps or below 3 per lap, or a bad
// twist_deg (see ring_twist_laps).
TrivariateBSpline<glm::dvec3> ring_lattice(const glm::dvec3& center, double radius, double width, double height,
                                           const glm::ivec3& controls, const glm::ivec3& order, double twist_deg = 0.0);

}  // namespace trispline::core
