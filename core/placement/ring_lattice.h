// A ring-shaped control lattice, periodic along u, for objects travelling around a ring without a seam (seed §4.5,
// Fig. 4.5).
#pragma once

#include <glm/glm.hpp>

#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// Control points of a periodic-in-u lattice around `center`.
// The circle of control points is enlarged so that the B-spline's centre line passes through radius `radius`
// at the control points' parameters (a uniform B-spline over a control polygon on a circle lies inside it).
// Throws std::invalid_argument on bad sizes (non-positive or non-finite sizes, radius ≤ width / 2, orders outside 2..4,
// fewer control points than the order).
TrivariateBSpline<glm::dvec3> ring_lattice(const glm::dvec3& center, double radius, double width, double height,
                                           const glm::ivec3& controls, const glm::ivec3& order);

}  // namespace trispline::core
